"""A benchmark's or test's own node on the bus: a bare presence on the wire (diffctl.bus.participant) with raw
endpoints, synchronous service calls and the graph, naming as a node does (`~`, the namespace, remaps), and a
clock (wall time, or /clock with `use_sim_time`). It has none of a ROS node's parameters or services: what is
measured or tested are diffctl's own nodes, not the probe."""

from __future__ import annotations

import signal
import struct
import threading
import time
from typing import Any

from diffctl.bus.participant import Participant
from diffctl.client.ros_logging import get_logger


class Probe(Participant):
    def __init__(self, name: str, namespace: str = "/", *, remaps: dict[str, str] | None = None,
                 use_sim_time: bool = False) -> None:
        ns = "/" + namespace.strip("/") if namespace.strip("/") else "/"
        super().__init__(name, ns, get_logger(name if ns == "/" else f"{ns[1:]}/{name}".replace("/", ".")))
        self._remaps = {self._expand(k): self._expand(v) for k, v in (remaps or {}).items()}
        self._sim_ns: int | None = None
        if use_sim_time:
            self._sim_ns = 0
            self.create_subscription("/clock", "rosgraph_msgs/msg/Clock", self._on_clock, raw=True)

    def _on_clock(self, data: bytes) -> None:
        sec, nanosec = struct.unpack_from("<iI", data, 4)
        self._sim_ns = sec * 1_000_000_000 + nanosec

    def _expand(self, name: str) -> str:
        if name.startswith("~"):
            return self.fqn + name[1:]
        return name if name.startswith("/") else f"{self.namespace.rstrip('/')}/{name}"

    def resolve(self, name: str) -> str:
        full = self._expand(name)
        return self._remaps.get(full, full)

    def now_ns(self) -> int:
        return time.time_ns() if self._sim_ns is None else self._sim_ns

    def spin(self) -> None:
        """Until SIGINT or SIGTERM (a test's helper process), then close."""
        stop = threading.Event()
        for sig in (signal.SIGINT, signal.SIGTERM):
            signal.signal(sig, lambda *_: stop.set())
        stop.wait()
        self.close()


def call(p: Participant, service: str, srv_type: str, request: dict[str, Any] | None = None,
         timeout_s: float = 10.0) -> Any:
    """One call of `service`, waiting (bounded) for it to be served."""
    client = p.create_client(service, srv_type)
    try:
        if not client.wait_for_service(timeout_s):
            raise AssertionError(f"{service} is not served")
        return client.call(request or {}, timeout=timeout_s)
    finally:
        p.destroy(client)
