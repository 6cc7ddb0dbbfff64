"""Gazebo-area fixtures: a router port of the test's own for launches that embed their router."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from tests.conftest import free_port


@pytest.fixture
def stack_env(monkeypatch: pytest.MonkeyPatch) -> Iterator[str]:
    from diffctl.bus.session import close_session

    endpoint = f"tcp/127.0.0.1:{free_port()}"
    monkeypatch.setenv("DIFFCTL_ROUTER", endpoint)
    yield endpoint
    close_session()
