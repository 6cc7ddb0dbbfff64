"""`launch.logging.get_logger`: the loggers launch files and OpaqueFunctions log through.

As launch's: a standard `logging.Logger` of that name (level INFO), printed on the screen in launch's screen
format `[LEVEL] [name]: message` (`[INFO] [my_launch]: …`, `[WARNING] …`), not passed on to the root logger.
"""

from __future__ import annotations

import logging
import sys

SCREEN_FORMAT = "[%(levelname)s] [%(name)s]: %(message)s"


class _Screen(logging.StreamHandler):  # type: ignore[type-arg]
    """Writes to whatever sys.stdout is at the time (tests and the launcher may replace it)."""

    def __init__(self) -> None:
        super().__init__(sys.stdout)
        self.setFormatter(logging.Formatter(SCREEN_FORMAT))

    def emit(self, record: logging.LogRecord) -> None:
        self.stream = sys.stdout
        super().emit(record)
        self.flush()


def get_logger(name: str | None = None) -> logging.Logger:
    logger = logging.getLogger(name or "launch")
    if not any(isinstance(h, _Screen) for h in logger.handlers):
        logger.addHandler(_Screen())
        logger.propagate = False
        if logger.level == logging.NOTSET:
            logger.setLevel(logging.INFO)
    return logger
