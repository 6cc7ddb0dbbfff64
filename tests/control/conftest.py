"""The control tests' shared fixture: a router and a client context for a whole module of controller tests."""

from __future__ import annotations

import os
import subprocess
from collections.abc import Iterator

import pytest

from bench.ports import free_port, wait_port
from tests.conftest import Procs


@pytest.fixture(scope="module")
def client_bus() -> Iterator[str]:
    """A real router on a free port and an initialised client context, kept for the module (controller nodes
    come and go per test); the realtime publishers' thread is restored afterwards."""
    from diffctl.bus.session import close_session
    from diffctl.client import runtime
    from diffctl.client.signals import SignalHandlerOptions
    from diffctl.control import realtime_publisher

    port = free_port()
    endpoint = f"tcp/127.0.0.1:{port}"
    old = os.environ.get("DIFFCTL_ROUTER")
    os.environ["DIFFCTL_ROUTER"] = endpoint
    procs = Procs()
    thread = realtime_publisher._thread
    try:
        procs.diffctl("router", "--listen", endpoint, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        wait_port(port)
        runtime.init(args=["test_controllers"], signal_handler_options=SignalHandlerOptions.NO)
        yield endpoint
    finally:
        runtime.try_shutdown()
        close_session()
        procs.close()
        realtime_publisher._thread = thread
        if old is None:
            os.environ.pop("DIFFCTL_ROUTER", None)
        else:
            os.environ["DIFFCTL_ROUTER"] = old
