"""Node logging in the rclcpp console format, line-buffered on stderr, with rate limiting for floods."""

from __future__ import annotations

import sys
import threading
import time

_LEVELS = {"DEBUG": 10, "INFO": 20, "WARN": 30, "ERROR": 40, "FATAL": 50}


class Logger:
    def __init__(self, name: str, level: str = "INFO") -> None:
        self.name = name
        self.level = _LEVELS.get(level.upper(), 20)
        self._last: dict[str, float] = {}
        self._suppressed: dict[str, int] = {}
        self._lock = threading.Lock()

    def _emit(self, level: str, text: str) -> None:
        if _LEVELS[level] < self.level:
            return
        line = f"[{level}] [{time.time():.6f}] [{self.name}]: {text}\n"
        try:
            sys.stderr.write(line)
            sys.stderr.flush()
        except (ValueError, OSError):
            pass

    def debug(self, text: str) -> None:
        self._emit("DEBUG", text)

    def info(self, text: str) -> None:
        self._emit("INFO", text)

    def warn(self, text: str) -> None:
        self._emit("WARN", text)

    warning = warn

    def error(self, text: str) -> None:
        self._emit("ERROR", text)

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
