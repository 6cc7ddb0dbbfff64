"""The simulator's log lines: rcutils' console format through the client's logging (one format for every
process), Gazebo's verbosity (`gz sim -v N`) as the level of the simulator's logger unless `--log-level` names
it, and floods (a malformed sample per message) throttled per key, counting what was left out."""

from __future__ import annotations

import threading
import time

from diffctl.client import ros_logging
from diffctl.client.ros_logging import LoggingSeverity


class Logger:
    def __init__(self, name: str, level: str = "INFO") -> None:
        self.name = name
        if ros_logging.get_logger_level(name) == LoggingSeverity.UNSET:
            ros_logging.set_logger_level(name, LoggingSeverity[level.upper()])
        self._logger = ros_logging.get_logger(name)
        self._last: dict[str, tuple[float, int]] = {}
        self._lock = threading.Lock()

    def debug(self, text: str) -> None:
        self._logger.debug(text)

    def info(self, text: str) -> None:
        self._logger.info(text)

    def warn(self, text: str) -> None:
        self._logger.warning(text)

    warning = warn

    def error(self, text: str) -> None:
        self._logger.error(text)

    def fatal(self, text: str) -> None:
        self._logger.fatal(text)

    def throttled(self, key: str, text: str, period_s: float = 5.0, level: str = "WARN") -> None:
        """At most once per period per key, saying how many were suppressed in between."""
        now = time.monotonic()
        with self._lock:
            last, suppressed = self._last.get(key, (-period_s, 0))
            if now - last < period_s:
                self._last[key] = (last, suppressed + 1)
                return
            self._last[key] = (now, 0)
        text += f" ({suppressed} more suppressed)" if suppressed else ""
        {"ERROR": self.error, "INFO": self.info, "DEBUG": self.debug}.get(level, self.warn)(text)
