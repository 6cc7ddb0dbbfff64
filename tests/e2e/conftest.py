"""End-to-end fixtures: each test gets its own router port, so nothing collides with a user's stack."""

from __future__ import annotations

import pytest

from tests.conftest import free_port


@pytest.fixture
def stack_env(monkeypatch: pytest.MonkeyPatch) -> str:
    from diffctl.bus.session import close_session

    endpoint = f"tcp/127.0.0.1:{free_port()}"
    monkeypatch.setenv("DIFFCTL_ROUTER", endpoint)
    yield endpoint
    close_session()
