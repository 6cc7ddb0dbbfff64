"""rclpy.logging: named loggers with rcutils' levels, call-site filters, the console format and /rosout.

Levels are per name and inherited along the dotted hierarchy, INFO by default. Console lines follow
RCUTILS_CONSOLE_OUTPUT_FORMAT (default `[{severity}] [{time}] [{name}]: {message}`) on stderr, or stdout with
RCUTILS_LOGGING_USE_STDOUT=1. A logger named as a node (or a child of it) also goes to that node's /rosout.
"""

from __future__ import annotations

import datetime
import enum
import inspect
import os
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class LogRecord:
    """One emitted line, as rcl_interfaces/msg/Log carries it to /rosout."""

    stamp_ns: int
    level: int
    name: str
    msg: str
    file: str
    function: str
    line: int


class LoggingSeverity(enum.IntEnum):
    UNSET = 0
    DEBUG = 10
    INFO = 20
    WARN = 30
    ERROR = 40
    FATAL = 50


_levels: dict[str, LoggingSeverity] = {}
_default_level = LoggingSeverity.INFO
_rosout: dict[str, Callable[[LogRecord], None]] = {}
_lock = threading.Lock()
_THIS = os.path.realpath(__file__)
_DEFAULT_FORMAT = "[{severity}] [{time}] [{name}]: {message}"


_console = True  # --disable-stdout-logs turns the console output off, as in rcl
rosout_enabled = True  # --disable-rosout-logs: no node publishes its log lines on /rosout


def configure_from_args(argv: list[str]) -> None:
    """`--log-level LEVEL`, `--log-level name:=LEVEL` and the stdout/rosout switches inside --ros-args, as rcl
    reads them at init."""
    global _default_level, _console, rosout_enabled
    from diffctl.ros_args import split_argv

    _, ros = split_argv(list(argv))
    for flag in ros:
        if flag in ("--disable-stdout-logs", "--enable-stdout-logs"):
            _console = flag.startswith("--enable")
        elif flag in ("--disable-rosout-logs", "--enable-rosout-logs"):
            rosout_enabled = flag.startswith("--enable")
    for i, a in enumerate(ros[:-1]):
        if a != "--log-level":
            continue
        spec = ros[i + 1]
        name, _, level = spec.rpartition(":=")
        try:
            sev = get_logging_severity_from_string(level)
        except RuntimeError:
            continue
        if name:
            _levels[name] = sev
        else:
            _default_level = sev


def get_logging_severity_from_string(log_severity: str) -> LoggingSeverity:
    """rcutils' names, in any case (UNSET, DEBUG, INFO, WARN, ERROR, FATAL)."""
    try:
        return LoggingSeverity[log_severity.upper()]
    except KeyError:
        raise RuntimeError("Failed to get severity name") from None


def set_logger_level(name: str, level: int | LoggingSeverity, detailed_error: bool = False) -> None:
    """The empty name is the root: its level is the default every unset logger inherits (UNSET included,
    which lets every severity through, as rcutils does)."""
    global _default_level
    severity = LoggingSeverity(level)
    if name:
        _levels[name] = severity
    else:
        _default_level = severity


def get_logger_level(name: str) -> LoggingSeverity:
    return _levels.get(name, LoggingSeverity.UNSET) if name else _default_level


def get_logger_effective_level(name: str) -> LoggingSeverity:
    n = name
    while n:
        lvl = _levels.get(n)
        if lvl is not None and lvl != LoggingSeverity.UNSET:
            return lvl
        n = n.rpartition(".")[0]
    return _default_level


def attach_rosout(name: str, sink: Callable[[LogRecord], None]) -> None:
    with _lock:
        _rosout[name] = sink


def detach_rosout(name: str, sink: Callable[[LogRecord], None] | None = None) -> None:
    with _lock:
        # `==`: a bound method (Rosout._sink) is a new object at each access, equal but not identical
        if sink is None or _rosout.get(name) == sink:
            _rosout.pop(name, None)


def _rosout_sink(name: str) -> Callable[[LogRecord], None] | None:
    n = name
    while n:
        sink = _rosout.get(n)
        if sink is not None:
            return sink
        n = n.rpartition(".")[0]
    return None


def _format(severity: LoggingSeverity, name: str, message: str, function: str, file: str, line: int,
            stamp_ns: int) -> str:
    fmt = os.environ.get("RCUTILS_CONSOLE_OUTPUT_FORMAT") or _DEFAULT_FORMAT
    sec, nsec = divmod(stamp_ns, 1_000_000_000)
    values = {
        "severity": severity.name, "name": name, "message": message, "function_name": function,
        "file_name": file, "line_number": str(line), "time": f"{sec}.{nsec:09d}",
        "time_as_nanoseconds": str(stamp_ns),
        "date_time_with_ms": datetime.datetime.fromtimestamp(stamp_ns / 1e9).strftime("%Y-%m-%d %H:%M:%S.%f")[:-3],
    }
    out = fmt
    for key, val in values.items():
        out = out.replace("{" + key + "}", val)
    return out


# rcutils' colours on a terminal (RCUTILS_COLORIZED_OUTPUT=1 forces them, 0 turns them off).
_COLORS = {LoggingSeverity.DEBUG: "\033[32m", LoggingSeverity.INFO: "\033[0m", LoggingSeverity.WARN: "\033[33m",
           LoggingSeverity.ERROR: "\033[31m", LoggingSeverity.FATAL: "\033[31m"}


def _colorize(stream: Any) -> bool:
    wanted = os.environ.get("RCUTILS_COLORIZED_OUTPUT")
    if wanted in ("0", "1"):
        return wanted == "1"
    try:
        return stream.isatty()
    except (AttributeError, ValueError):
        return False


def rcutils_log(severity: LoggingSeverity, name: str, message: str, function: str, file: str, line: int) -> None:
    stamp_ns = time.time_ns()
    stream = sys.stdout if os.environ.get("RCUTILS_LOGGING_USE_STDOUT") == "1" else sys.stderr
    text = _format(severity, name, message, function, file, line, stamp_ns)
    color = _COLORS.get(severity) if _colorize(stream) else None
    if color:
        text = f"{color}{text}\033[0m"
    try:
        if _console:
            stream.write(text + "\n")
        stream.flush()
    except (ValueError, OSError):
        pass
    sink = _rosout_sink(name)
    if sink is not None:
        try:
            sink(LogRecord(stamp_ns, int(severity), name, message, file, function, line))
        except Exception:
            pass  # logging must never fail the code that logs



def _caller() -> tuple[str, str, int, int]:
    frame = inspect.currentframe()
    while frame is not None and os.path.realpath(frame.f_code.co_filename) == _THIS:
        frame = frame.f_back
    if frame is None:
        return "", "", 0, 0
    return frame.f_code.co_name, os.path.abspath(frame.f_code.co_filename), frame.f_lineno, frame.f_lasti


# Each call-site filter and the options it keeps from its first call (later calls may not change them)
_FILTER_OPTIONS = {"throttle": ("throttle_duration_sec", "throttle_time_source_type"),
                   "skip_first": ("skip_first",), "once": ("once",)}
_FILTER_PARAMS = [p for opts in _FILTER_OPTIONS.values() for p in opts]


def _filters(kwargs: dict[str, Any]) -> list[str]:
    for k in kwargs:
        if k not in _FILTER_PARAMS:
            raise TypeError(f'parameter "{k}" is not one of the recognized logging options "{_FILTER_PARAMS}"')
    out = []
    if kwargs.get("throttle_duration_sec") or kwargs.get("throttle_time_source_type"):
        if not kwargs.get("throttle_duration_sec"):
            raise TypeError('required parameter "throttle_duration_sec" not specified but is required for the '
                            'the logging filter "throttle"')
        out.append("throttle")
    if kwargs.get("skip_first"):
        out.append("skip_first")
    if kwargs.get("once"):
        out.append("once")
    return out


class RcutilsLogger:
    """rclpy's logger: per call site filter state (throttle, skip_first, once)."""

    def __init__(self, name: str = "") -> None:
        self.name = name
        self.contexts: dict[tuple, dict[str, Any]] = {}

    def get_child(self, name: str) -> RcutilsLogger:
        if not name:
            raise ValueError("Child logger name must not be empty.")
        return RcutilsLogger(f"{self.name}.{name}" if self.name else name)

    def set_level(self, level: int | LoggingSeverity) -> None:
        set_logger_level(self.name, level)

    def get_effective_level(self) -> LoggingSeverity:
        return get_logger_effective_level(self.name)

    def is_enabled_for(self, severity: int | LoggingSeverity) -> bool:
        return LoggingSeverity(severity) >= get_logger_effective_level(self.name)

    def log(self, message: str, severity: int | LoggingSeverity, **kwargs: Any) -> bool:
        severity = LoggingSeverity(severity)
        if not self.is_enabled_for(severity):
            return False
        name = kwargs.pop("name", self.name)
        filters = _filters(kwargs)
        function, file, line, lasti = _caller()
        key = (function, file, line, lasti)
        ctx = self.contexts.get(key)
        params = {p: kwargs.get(p) for f in filters for p in _FILTER_OPTIONS[f]}
        if ctx is None:
            ctx = {"name": name, "severity": severity, "filters": filters, "params": params,
                   "last_ns": 0, "skipped": False, "logged_once": False}
            clock = kwargs.get("throttle_time_source_type")
            if clock is not None:
                from diffctl.client.clock import Clock

                if not isinstance(clock, Clock):
                    raise ValueError(f'Received throttle_time_source_type of "{clock}" is not a clock instance')
            self.contexts[key] = ctx
        else:
            if severity != ctx["severity"]:
                raise ValueError("Logger severity cannot be changed between calls.")
            if name != ctx["name"]:
                raise ValueError("Logger name cannot be changed between calls.")
            if filters != ctx["filters"]:
                raise ValueError("Requested logging filters cannot be changed between calls.")
            if params != ctx["params"]:
                raise ValueError("Logging filter parameters cannot be changed between calls.")
        for f in filters:
            if f == "throttle":
                clock = kwargs.get("throttle_time_source_type")
                now = clock.now().nanoseconds if clock is not None else time.time_ns()
                if now < ctx["last_ns"] + kwargs["throttle_duration_sec"] * 1e9:
                    return False
                ctx["last_ns"] = now
            elif f == "skip_first":
                if not ctx["skipped"]:
                    ctx["skipped"] = True
                    return False
            elif f == "once":
                if ctx["logged_once"]:
                    return False
                ctx["logged_once"] = True
        if not isinstance(message, str):
            raise TypeError(
                "rclpy_logging_rcutils_log(): incompatible function arguments. The following argument types are "
                "supported:\n    1. (arg0: typing.SupportsInt, arg1: str, arg2: str, arg3: str, arg4: str, "
                "arg5: typing.SupportsInt) -> None\n\n"
                f"Invoked with: {severity!r}, {name!r}, {message!r}, {function!r}, {file!r}, {line}")
        rcutils_log(severity, name, message, function, file, line)
        return True

    def debug(self, message: str, **kwargs: Any) -> bool:
        return self.log(message, LoggingSeverity.DEBUG, **kwargs)

    def info(self, message: str, **kwargs: Any) -> bool:
        return self.log(message, LoggingSeverity.INFO, **kwargs)

    def warning(self, message: str, **kwargs: Any) -> bool:
        return self.log(message, LoggingSeverity.WARN, **kwargs)

    def warn(self, message: str, **kwargs: Any) -> bool:
        return self.log(message, LoggingSeverity.WARN, **kwargs)

    def error(self, message: str, **kwargs: Any) -> bool:
        return self.log(message, LoggingSeverity.ERROR, **kwargs)

    def fatal(self, message: str, **kwargs: Any) -> bool:
        return self.log(message, LoggingSeverity.FATAL, **kwargs)


_root_logger = RcutilsLogger()


def get_logger(name: str) -> RcutilsLogger:
    if not name:
        raise ValueError("Logger name must not be empty.")
    return _root_logger.get_child(name)


def initialize() -> None:
    pass


def shutdown() -> None:
    pass


def clear_config() -> None:
    global _default_level
    _levels.clear()
    _default_level = LoggingSeverity.INFO


def get_logging_directory() -> Any:
    from pathlib import Path

    return Path(os.environ.get("ROS_LOG_DIR") or Path(os.environ.get("ROS_HOME", Path.home() / ".ros")) / "log")
