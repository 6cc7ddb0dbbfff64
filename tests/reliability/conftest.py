"""Fault-test fixtures: a private router port per test (the launcher's embedded one, or a separate router)."""

from __future__ import annotations

import subprocess
from collections.abc import Iterator

import pytest

from tests.conftest import Procs, free_port, wait_port


@pytest.fixture
def stack_env(monkeypatch: pytest.MonkeyPatch) -> Iterator[str]:
    """A free endpoint for the launcher's embedded router, set as DIFFCTL_ROUTER for the test and its children."""
    from diffctl.bus.session import close_session

    endpoint = f"tcp/127.0.0.1:{free_port()}"
    monkeypatch.setenv("DIFFCTL_ROUTER", endpoint)
    yield endpoint
    close_session()


@pytest.fixture
def separate_router(stack_env: str) -> Iterator[str]:
    """A `diffctl router` of its own at stack_env, so the launcher can be paused without pausing the bus."""
    ps = Procs()
    try:
        ps.diffctl("router", "--listen", stack_env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        wait_port(int(stack_env.rsplit(":", 1)[1]))
        yield stack_env
    finally:
        ps.close()
