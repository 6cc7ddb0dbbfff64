"""A test driver for robot_localization's nodes on a real router: it owns /clock (the nodes run on sim time),
publishes stamped sensor messages and watches what the nodes publish."""

from __future__ import annotations

import math
import threading
import time
from typing import Any

from diffctl.interfaces import types
from tests.probe import Probe

SEC = 1_000_000_000


def _time(ns: int) -> dict:
    return {"sec": ns // SEC, "nanosec": ns % SEC}


def yaw_of(q: Any) -> float:
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def rpy_of(q: Any) -> tuple[float, float, float]:
    sinp = 2.0 * (q.w * q.y - q.z * q.x)
    pitch = math.copysign(math.pi / 2, sinp) if abs(sinp) >= 1 else math.asin(sinp)
    roll = math.atan2(2.0 * (q.w * q.x + q.y * q.z), 1.0 - 2.0 * (q.x * q.x + q.y * q.y))
    return roll, pitch, yaw_of(q)


def quat_rpy(roll: float, pitch: float, yaw: float) -> dict:
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return {"x": sr * cp * cy - cr * sp * sy, "y": cr * sp * cy + sr * cp * sy,
            "z": cr * cp * sy - sr * sp * cy, "w": cr * cp * cy + sr * sp * sy}


class Driver:
    """Sim time starts at 100 s; `step` advances it, stamps messages with it and keeps the nodes in step."""

    def __init__(self, name: str = "rl_test_driver", start_ns: int = 100 * SEC) -> None:
        self.node = Probe(name)
        self.now_ns = start_ns  # the stamp of the next message
        self.clock_ns = start_ns  # what /clock last said: never behind now_ns, never backwards
        self.clock = self.node.create_publisher("/clock", "rosgraph_msgs/msg/Clock")
        self.lock = threading.Lock()
        self.last: dict[str, Any] = {}
        self.count: dict[str, int] = {}
        self.pubs: dict[str, Any] = {}
        self.tick()

    def tick(self, ahead_ns: int = 0) -> None:
        """/clock at now (or `ahead_ns` further than it said last): the nodes' timers run on it."""
        self.clock_ns = max(self.now_ns, self.clock_ns + ahead_ns)
        self.clock.publish({"clock": _time(self.clock_ns)})

    def watch(self, topic: str, typename: str) -> None:
        def keep(m: Any) -> None:
            with self.lock:
                self.last[topic] = m
                self.count[topic] = self.count.get(topic, 0) + 1

        self.node.create_subscription(topic, typename, keep)

    def latest(self, topic: str) -> Any:
        with self.lock:
            return self.last.get(topic)

    def forget(self, topic: str) -> None:
        with self.lock:
            self.last.pop(topic, None)

    def publisher(self, topic: str, typename: str, *, subscribers: int = 1, wait_s: float = 30.0) -> Any:
        """A publisher on `topic` once `subscribers` nodes subscribe to it (nothing published is lost)."""
        if topic not in self.pubs:
            pub = self.node.create_publisher(topic, typename)
            deadline = time.monotonic() + wait_s
            while pub.subscription_count < subscribers:
                assert time.monotonic() < deadline, f"{pub.subscription_count} of {subscribers} subscribe to {topic}"
                time.sleep(0.01)
            self.pubs[topic] = pub
        return self.pubs[topic]

    def stamped(self, values: dict) -> dict:
        return {**values, "header": {**values.get("header", {}), "stamp": _time(self.now_ns)}}

    def wait_output(self, topic: str, stamp_ns: int, timeout_s: float = 30.0) -> Any:
        """The first output on `topic` stamped `stamp_ns` or later (the clock is nudged on while waiting)."""
        deadline = time.monotonic() + timeout_s
        while True:
            m = self.latest(topic)
            if m is not None and types.time_ns(m.header.stamp) >= stamp_ns:
                return m
            assert time.monotonic() < deadline, f"{topic} never reached {stamp_ns / 1e9} s (last: {m})"
            self.tick(10_000_000)
            time.sleep(0.005)

    def drive(self, topic: str, typename: str, make: Any, n: int, dt_s: float, out: str = "/odometry/filtered",
              every: int = 5) -> Any:
        """Publish `make(i)` (a dict, stamped now) n times, dt_s of sim time apart; wait for the filter to take
        each batch of `every` (within its queue depth; 0: no wait) and return its last output."""
        pub = self.publisher(topic, typename)
        for i in range(n):
            self.now_ns += int(dt_s * SEC)
            self.tick()
            pub.publish(self.stamped(make(i)))
            if every and ((i + 1) % every == 0 or i == n - 1):
                self.wait_output(out, self.now_ns)
        return self.latest(out)

    def call(self, service: str, typename: str, request: dict | None = None) -> Any:
        cli = self.node.create_client(service, typename)
        assert cli.wait_for_service(30.0), f"{service} never came up"
        return cli.call(request or {}, timeout=10.0)

    def close(self) -> None:
        self.node.close()
