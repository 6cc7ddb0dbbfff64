"""Every handler class of `logging` and `logging.handlers`, able to format each logger its own way.

`launch.logging.handlers.StreamHandler` (and `FileHandler`, `WatchedFileHandler`, `Handler`, …) are the
standard classes with two more methods, `setFormatterFor(logger, formatter)` and
`unsetFormatterFor(logger)`: a record from a logger with a formatter of its own is formatted with that one,
the rest with the handler's formatter. This lets one screen handler print launch's own messages as
`[INFO] [name]: msg` and a process's output lines bare. The classes are built on first use.
"""

from __future__ import annotations

import logging
from typing import Any

_made: dict[str, type] = {}


def with_per_logger_formatting(cls: type) -> type:
    """A subclass of the handler class `cls` with per-logger formatters."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        cls.__init__(self, *args, **kwargs)
        self._formatters = {}

    def setFormatterFor(self, logger: Any, formatter: logging.Formatter) -> None:
        self._formatters[logger if isinstance(logger, str) else logger.name] = formatter

    def unsetFormatterFor(self, logger: Any) -> None:
        self._formatters.pop(logger if isinstance(logger, str) else logger.name, None)

    def format(self, record: logging.LogRecord) -> str:
        own = self._formatters.get(record.name)
        return own.format(record) if own is not None else cls.format(self, record)

    return type(cls.__name__, (cls,), {
        '__init__': __init__, 'setFormatterFor': setFormatterFor, 'unsetFormatterFor': unsetFormatterFor,
        'format': format, '__doc__': cls.__doc__, '__module__': __name__, '__qualname__': cls.__name__,
    })


def _standard_handler(name: str) -> type | None:
    import logging.handlers

    for module in (logging, logging.handlers):
        candidate = getattr(module, name, None)
        if isinstance(candidate, type) and issubclass(candidate, logging.Handler):
            return candidate
    return None


def __getattr__(name: str) -> Any:
    if name.startswith('_'):
        raise AttributeError(name)
    made = _made.get(name)
    if made is not None:
        return made
    standard = _standard_handler(name)
    if standard is None:
        import logging.handlers

        try:
            return getattr(logging.handlers, name)
        except AttributeError:
            return getattr(logging, name)
    made = _made[name] = with_per_logger_formatting(standard)
    return made


def __dir__() -> list[str]:
    import logging.handlers

    names = {n for m in (logging, logging.handlers) for n in dir(m) if _standard_handler(n) is not None}
    return sorted(names | set(globals()))
