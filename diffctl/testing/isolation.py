"""Each launch test on a bus of its own: a Zenoh router on a free loopback port and a ROS_DOMAIN_ID nobody
else on this machine holds, so tests run in parallel without hearing each other.

The domain is held by an advisory lock on a file (as ros2test's domain_coordinator holds a port): free again
as soon as the process holding it ends, however it ends.
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import random
import socket
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

DOMAINS = range(1, 102)  # rmw_zenoh takes 0..232; ros2test's coordinator hands out 1..101 as well


@dataclass(frozen=True)
class Bus:
    endpoint: str
    domain_id: int


def free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@contextlib.contextmanager
def _domain() -> Iterator[int]:
    folder = Path(tempfile.gettempdir()) / "diffctl-test-domains"
    folder.mkdir(exist_ok=True)
    candidates = list(DOMAINS)
    random.shuffle(candidates)
    for domain in candidates:
        fd = os.open(folder / f"{domain}.lock", os.O_CREAT | os.O_RDWR, 0o600)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(fd)
            continue
        try:
            yield domain
        finally:
            fcntl.flock(fd, fcntl.LOCK_UN)
            os.close(fd)
        return
    raise RuntimeError(f"every ROS_DOMAIN_ID of {DOMAINS.start}..{DOMAINS.stop - 1} is held by a running test")


@contextlib.contextmanager
def isolated_bus() -> Iterator[Bus]:
    """Start a router, point this process (and so every child) at it, in a domain of its own; undo after."""
    from diffctl.bus.router import start_router
    from diffctl.bus.session import close_session

    saved = {k: os.environ.get(k) for k in ("DIFFCTL_ROUTER", "ROS_DOMAIN_ID")}
    with _domain() as domain:
        router = None
        for _ in range(5):  # a port found free may be taken before the router binds it
            endpoint = f"tcp/127.0.0.1:{free_port()}"
            try:
                router = start_router([endpoint])
                break
            except Exception:
                continue
        if router is None:
            raise RuntimeError("cannot start a Zenoh router on a free loopback port")
        close_session()  # a session of this process opened before belongs to another bus
        os.environ["DIFFCTL_ROUTER"] = endpoint
        os.environ["ROS_DOMAIN_ID"] = str(domain)
        try:
            yield Bus(endpoint, domain)
        finally:
            close_session()
            router.close()
            for key, value in saved.items():
                if value is None:
                    os.environ.pop(key, None)
                else:
                    os.environ[key] = value
