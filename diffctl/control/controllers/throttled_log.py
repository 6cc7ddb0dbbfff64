"""Rate-limited logging for controllers: a stream of bad commands must not flood the console.

`ThrottledLog(node.log).warn("stale", text)` prints at most once per `period_s` (wall time) per key and says
how many similar messages it held back in between; `once(key, text)` prints a key only the first time.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any


class ThrottledLog:
    def __init__(self, log: Any, period_s: float = 2.0, clock: Callable[[], float] = time.monotonic) -> None:
        self.log = log
        self.period_s = period_s
        self._clock = clock
        self._last: dict[str, float] = {}
        self._held: dict[str, int] = {}
        self._seen: set[str] = set()

    def _emit(self, key: str, text: str, sink: Callable[[str], None]) -> None:
        now = self._clock()
        last = self._last.get(key)
        if last is not None and now - last < self.period_s:
            self._held[key] = self._held.get(key, 0) + 1
            return
        held = self._held.pop(key, 0)
        self._last[key] = now
        sink(f"{text} ({held} similar message(s) held back)" if held else text)

    def warn(self, key: str, text: str) -> None:
        self._emit(key, text, self.log.warn)

    def error(self, key: str, text: str) -> None:
        self._emit(key, text, self.log.error)

    def once(self, key: str, text: str) -> None:
        if key not in self._seen:
            self._seen.add(key)
            self.log.warn(text)
