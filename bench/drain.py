"""Timing a flood honestly: the window runs until the receiver has taken the last message, not until the sender
stopped, so messages that arrive after the sender's window count only with the time they took to arrive."""

from __future__ import annotations

import time
from collections.abc import Callable


def drained(count: Callable[[], int], quiet_s: float = 0.25, poll_s: float = 0.002,
            limit_s: float = 10.0) -> tuple[int, float]:
    """Call when the sender has stopped: polls `count()` until it has not grown for `quiet_s`; returns (the
    final count, the monotonic time it was last seen to grow — now, if it never grew after the call)."""
    last = count()
    t_last = time.monotonic()
    deadline = t_last + limit_s
    while True:
        time.sleep(poll_s)
        now = time.monotonic()
        c = count()
        if c != last:
            last, t_last = c, now
        elif now - t_last >= quiet_s or now >= deadline:
            return last, t_last
