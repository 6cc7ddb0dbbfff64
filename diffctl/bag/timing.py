"""Playback time: where in the bag "now" is, at a rate, paused or not. Pure: the wall clock is passed in.

Bag time advances at `rate` × wall time from an anchor (a bag time and the wall time it was reached).
Every change — rate, pause, resume, a step to the next message, a loop back to the start — re-anchors,
so the mapping stays continuous and no message is hurried or held by a change of speed.
"""

from __future__ import annotations

import math
from collections.abc import Callable

from diffctl.errors import ConfigError

MIN_RATE = 0.01


def check_rate(rate: float, what: str = "--rate") -> float:
    if not math.isfinite(rate) or rate < MIN_RATE:
        raise ConfigError(f"{what} {rate!r} must be a positive number (at least {MIN_RATE})")
    return rate


class PlaybackTimer:
    def __init__(self, start_bag_ns: int, rate: float, now_s: Callable[[], float], *, paused: bool = False) -> None:
        self._now_s = now_s
        self.rate = check_rate(rate)
        self.paused = paused
        self._anchor_bag_ns = start_bag_ns
        self._anchor_wall_s = now_s()

    def bag_now_ns(self) -> int:
        """The bag time that corresponds to now."""
        if self.paused:
            return self._anchor_bag_ns
        return self._anchor_bag_ns + round((self._now_s() - self._anchor_wall_s) * self.rate * 1e9)

    def wall_at(self, bag_ns: int) -> float:
        """The wall time (in `now_s` units) at which bag time `bag_ns` is reached (inf while paused)."""
        if self.paused:
            return math.inf
        return self._anchor_wall_s + (bag_ns - self._anchor_bag_ns) / (self.rate * 1e9)

    def jump_to(self, bag_ns: int) -> None:
        """Bag time is `bag_ns` now (a step, a loop, a start offset)."""
        self._anchor_bag_ns = bag_ns
        self._anchor_wall_s = self._now_s()

    def set_rate(self, rate: float) -> None:
        check_rate(rate)
        self.jump_to(self.bag_now_ns())
        self.rate = rate

    def pause(self) -> None:
        if not self.paused:
            self.jump_to(self.bag_now_ns())
            self.paused = True

    def resume(self) -> None:
        if self.paused:
            self._anchor_wall_s = self._now_s()
            self.paused = False

    def toggle(self) -> bool:
        """Pause or resume; returns whether it is paused now."""
        (self.resume if self.paused else self.pause)()
        return self.paused
