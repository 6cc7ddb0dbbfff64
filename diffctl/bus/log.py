"""Node logging in the rclcpp console format, line-buffered on stderr, with rate limiting for floods.

A node attaches a sink (its `/rosout` publisher) that receives every emitted line with its level, the
caller's file, function and line, and the same wall-clock stamp the console line shows.
"""

from __future__ import annotations

import os
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass

_LEVELS = {"DEBUG": 10, "INFO": 20, "WARN": 30, "ERROR": 40, "FATAL": 50}
_THIS_FILE = os.path.normcase(__file__)


@dataclass(frozen=True)
class LogRecord:
    """One emitted line, as rcl_interfaces/msg/Log carries it."""

    stamp_ns: int
    level: int
    name: str
    msg: str
    file: str
    function: str
    line: int


def _caller() -> tuple[str, str, int]:
    # The first frame outside this module is the code that logged.
    f = sys._getframe(2)
    while f is not None and os.path.normcase(f.f_code.co_filename) == _THIS_FILE:
        f = f.f_back
    if f is None:
        return "", "", 0
    return f.f_code.co_filename, f.f_code.co_name, f.f_lineno


class Logger:
    def __init__(self, name: str, level: str = "INFO") -> None:
        self.name = name
        self.level = _LEVELS.get(level.upper(), 20)
        self._last: dict[str, float] = {}
        self._suppressed: dict[str, int] = {}
        self._lock = threading.Lock()
        self.sink: Callable[[LogRecord], None] | None = None

    def _emit(self, level: str, text: str) -> None:
        if _LEVELS[level] < self.level:
            return
        now_ns = time.time_ns()
        line = f"[{level}] [{now_ns / 1e9:.6f}] [{self.name}]: {text}\n"
        try:
            sys.stderr.write(line)
            sys.stderr.flush()
        except (ValueError, OSError):
            pass
        sink = self.sink
        if sink is not None:
            file, function, lineno = _caller()
            try:
                sink(LogRecord(now_ns, _LEVELS[level], self.name, text, file, function, lineno))
            except Exception:
                pass  # logging must never fail the code that logs

    def debug(self, text: str) -> None:
        self._emit("DEBUG", text)

    def info(self, text: str) -> None:
        self._emit("INFO", text)

    def warn(self, text: str) -> None:
        self._emit("WARN", text)

    warning = warn

    def error(self, text: str) -> None:
        self._emit("ERROR", text)

    def fatal(self, text: str) -> None:
        self._emit("FATAL", text)

    def throttled(self, key: str, text: str, period_s: float = 5.0, level: str = "WARN") -> None:
        """Log at most once per period per key, saying how many were suppressed in between."""
        now = time.monotonic()
        with self._lock:
            last = self._last.get(key)
            if last is not None and now - last < period_s:
                self._suppressed[key] = self._suppressed.get(key, 0) + 1
                return
            n = self._suppressed.pop(key, 0)
            self._last[key] = now
        self._emit(level, text + (f" ({n} more suppressed)" if n else ""))
