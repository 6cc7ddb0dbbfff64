"""Polling for a condition in tests that watch real processes."""

from __future__ import annotations

import time
from collections.abc import Callable


def wait_for(pred: Callable[[], bool], timeout_s: float = 10.0, every: Callable[[], None] | None = None) -> bool:
    """Whether `pred()` became true within `timeout_s`; `every()` runs before each look (e.g. publish again)."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if every:
            every()
        if pred():
            return True
        time.sleep(0.05)
    return pred()
