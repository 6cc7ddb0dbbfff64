"""`@ready_to_test_action_timeout(s)`: how long a launch test waits for its ReadyToTest (default 15 s)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any


def ready_to_test_action_timeout(timeout: float) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    def decorator(func: Callable[..., Any]) -> Callable[..., Any]:
        func.__ready_to_test_action_timeout__ = timeout  # type: ignore[attr-defined]
        return func

    return decorator
