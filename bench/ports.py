"""Loopback ports for benchmarks: a free one to put a private router on, and waiting for a listener."""

from __future__ import annotations

import os
import random
import socket
import time

# Under pytest-xdist, ports below the kernel's ephemeral range (32768-60999 here), split between the workers
XDIST_PORTS = range(20000, 32000)


def free_port() -> int:
    """A loopback port free now. Under pytest-xdist each worker takes its own ports (of XDIST_PORTS, those its
    number selects modulo the worker count), so two workers never pick the same one between its choice and its
    bind: a launch whose router port another worker's launch took first would join that router (a router
    already answers there) and lose it when that launch ends. Elsewhere the kernel picks."""
    worker = os.environ.get("PYTEST_XDIST_WORKER", "")
    count = int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1") or 1)
    if count <= 1 or not (worker.startswith("gw") and worker[2:].isdigit()):
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            return s.getsockname()[1]
    index = int(worker[2:]) % count
    slots = len(XDIST_PORTS) // count
    for _ in range(1000):
        port = XDIST_PORTS.start + index + count * random.randrange(slots)
        with socket.socket() as s:
            try:
                s.bind(("127.0.0.1", port))
            except OSError:
                continue  # taken: another
        return port
    raise OSError(f"no free port among worker {worker}'s share of {XDIST_PORTS}")


def wait_port(port: int, timeout_s: float = 10.0) -> None:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        try:
            with socket.create_connection(("127.0.0.1", port), timeout=0.2):
                return
        except OSError:
            time.sleep(0.01)
    raise TimeoutError(f"nothing listens on 127.0.0.1:{port} after {timeout_s} s")
