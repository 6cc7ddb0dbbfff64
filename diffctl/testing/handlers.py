"""proc_output and proc_info: what the processes of a launch test printed and how they started and ended.

As launch_testing's IoHandler/ActiveIoHandler and ProcInfoHandler/ActiveProcInfoHandler: the launch thread
appends events, the test thread reads and waits for them. The active ones (given to tests that run while the
launch does) can wait: `assertWaitFor`, `assertWaitForStartup`, `assertWaitForShutdown`.
"""

from __future__ import annotations

import re
import threading
import time
from collections.abc import Callable
from typing import Any

from diffctl.testing.proc_lookup import NoMatchingProcessException, process_name, resolve_processes

_ANSI = re.compile(r"\x1b\[[0-?]*[ -/]*[@-~]")


def strip_ansi(text: str) -> str:
    return _ANSI.sub("", text)


def set_process_details(event: Any) -> None:
    """launch's `action.process_details` (name, cmd, cwd, env, pid), filled when the process starts."""
    action = getattr(event, "action", None)
    if action is None:
        return
    try:
        action.process_details = {
            "name": event.name,
            "cmd": list(event.cmd),
            "cwd": event.cwd,
            "env": dict(event.env),
            "pid": event.pid,
        }
    except AttributeError:
        pass


def cache_output(event: Any) -> None:
    """launch's cached_output: the action keeps what its process printed (get_stdout/get_stderr)."""
    action = getattr(event, "action", None)
    cache = getattr(action, "output_cache", None)
    if cache is not None and getattr(action, "cached_output", False):
        cache["stdout" if event.from_stdout else "stderr"].append(event.text.decode(errors="replace"))


def record_exit(event: Any) -> None:
    action = getattr(event, "action", None)
    if action is not None and hasattr(action, "return_code"):
        action.return_code = event.returncode


def _find(text: str, expected: Any, start: int = 0) -> int | None:
    """Where the match of `expected` (a string or a compiled regex) in `text` from `start` ends, or None."""
    if isinstance(expected, str):
        at = text.find(expected, start)
        return None if at < 0 else at + len(expected)
    m = expected.search(text, start)
    return None if m is None else m.end()


def output_matches(text: str, expected: Any) -> bool:
    """A string or regex must be found; a list of them must all be found, in order, without overlapping."""
    items = list(expected) if isinstance(expected, (list, tuple)) else [expected]
    at = 0
    for item in items:
        end = _find(text, item, at)
        if end is None:
            return False
        at = end
    return True


class IoHandler:
    """Every ProcessIO event of a launch, in arrival order and per process."""

    def __init__(self) -> None:
        self._events: list[Any] = []
        self._by_action: dict[int, list[Any]] = {}
        self._actions: dict[int, Any] = {}
        self._lock = threading.Condition()

    def track(self, event: Any) -> None:
        """A process started: it is known (with no output yet)."""
        with self._lock:
            key = id(event.action)
            self._actions.setdefault(key, event.action)
            self._by_action.setdefault(key, [])
            self._lock.notify_all()

    def append(self, event: Any) -> None:
        with self._lock:
            key = id(event.action)
            self._actions.setdefault(key, event.action)
            self._events.append(event)
            self._by_action.setdefault(key, []).append(event)
            self._lock.notify_all()

    def __iter__(self):
        with self._lock:
            return iter(list(self._events))

    def processes(self) -> list[Any]:
        with self._lock:
            return list(self._actions.values())

    def process_names(self) -> list[str]:
        return [process_name(a) for a in self.processes()]

    def __getitem__(self, key: Any) -> list[Any]:
        with self._lock:
            if isinstance(key, str):
                for k, action in self._actions.items():
                    if process_name(action) == key:
                        return list(self._by_action[k])
                raise KeyError(key)
            return list(self._by_action[id(key)])

    def text(self, action: Any, stream: str, *, strip_ansi_escape_sequences: bool = True,
             output_filter: Callable[[str], str] | None = None) -> str:
        events = self[action]
        chunks = [e.text.decode(errors="replace") for e in events if _in_stream(e, stream)]
        text = "".join(chunks)
        if strip_ansi_escape_sequences:
            text = strip_ansi(text)
        if output_filter is not None:
            text = output_filter(text)
        return text


def _in_stream(event: Any, stream: str) -> bool:
    if stream == "stdout":
        return event.from_stdout
    if stream == "stderr":
        return event.from_stderr
    return True


class ActiveIoHandler(IoHandler):
    """proc_output while the launch runs: can wait for output."""

    def waitFor(
        self,
        expected_output: Any,
        process: Any = None,
        cmd_args: Any = None,
        *,
        strict_proc_matching: bool = True,
        output_filter: Callable[[str], str] | None = None,
        timeout: float = 10,
        strip_ansi_escape_sequences: bool = True,
        stream: str = "stderr",
    ) -> bool:
        deadline = time.monotonic() + timeout
        found_any = False
        with self._lock:
            while True:
                try:
                    actions = resolve_processes(
                        self, process, cmd_args, strict_proc_matching=strict_proc_matching
                    )
                    found_any = found_any or bool(actions)
                except NoMatchingProcessException:
                    actions = []
                for action in actions:
                    if id(action) not in self._by_action:
                        continue
                    text = self.text(
                        action,
                        stream,
                        strip_ansi_escape_sequences=strip_ansi_escape_sequences,
                        output_filter=output_filter,
                    )
                    if output_matches(text, expected_output):
                        return True
                left = deadline - time.monotonic()
                if left <= 0:
                    break
                self._lock.wait(left)
        if process is not None and not found_any:
            raise Exception(
                f"After timeout, found no processes matching '{process_name(process) or process}' "
                f"It either doesn't exist, was never launched, or didn't generate any output. "
                f"Processes: {', '.join(self.process_names()) or 'none'}"
            )
        return False

    def assertWaitFor(self, expected_output: Any, process: Any = None, cmd_args: Any = None, **kw: Any) -> None:
        success = self.waitFor(expected_output, process, cmd_args, **kw)
        if not success:
            raise AssertionError(f"Waiting for output timed out: {expected_output!r} not found on "
                                 f"{kw.get('stream', 'stderr')} of {_describe(self, process)}")


def _describe(handler: Any, process: Any) -> str:
    if process is None:
        return "any process (" + (", ".join(handler.process_names()) or "none") + ")"
    return process if isinstance(process, str) else (process_name(process) or repr(process))


class ProcInfoHandler:
    """The last event (ProcessStarted, then ProcessExited) of every process of a launch."""

    def __init__(self) -> None:
        self._info: dict[int, Any] = {}
        self._actions: dict[int, Any] = {}
        self._lock = threading.Condition()

    def append(self, event: Any) -> None:
        with self._lock:
            key = id(event.action)
            self._actions[key] = event.action
            self._info[key] = event
            self._lock.notify_all()

    def processes(self) -> list[Any]:
        with self._lock:
            return list(self._actions.values())

    def process_names(self) -> list[str]:
        return [process_name(a) for a in self.processes()]

    def __iter__(self):
        return iter(self.processes())

    def __getitem__(self, key: Any) -> Any:
        with self._lock:
            if isinstance(key, str):
                for k, action in self._actions.items():
                    if process_name(action) == key:
                        return self._info[k]
                raise KeyError(key)
            return self._info[id(key)]


class ActiveProcInfoHandler(ProcInfoHandler):
    """proc_info while the launch runs: can wait for a process to start or finish."""

    def _wait(self, process: Any, cmd_args: Any, timeout: float, strict: bool, done: Callable[[Any], bool]) -> bool:
        deadline = time.monotonic() + timeout
        with self._lock:
            while True:
                try:
                    actions = resolve_processes(self, process, cmd_args, strict_proc_matching=strict)
                except NoMatchingProcessException:
                    actions = []
                if any(id(a) in self._info and done(self._info[id(a)]) for a in actions):
                    return True
                left = deadline - time.monotonic()
                if left <= 0:
                    return False
                self._lock.wait(left)

    def waitForStartup(self, process: Any, cmd_args: Any = None, *, timeout: float = 10,
                       strict_proc_matching: bool = True) -> bool:
        return self._wait(process, cmd_args, timeout, strict_proc_matching, lambda e: True)

    def waitForShutdown(self, process: Any, cmd_args: Any = None, *, timeout: float = 10,
                        strict_proc_matching: bool = True) -> bool:
        return self._wait(process, cmd_args, timeout, strict_proc_matching, lambda e: hasattr(e, "returncode"))

    def assertWaitForStartup(self, process: Any = None, cmd_args: Any = None, *, timeout: float = 10,
                             strict_proc_matching: bool = True) -> None:
        if not self.waitForStartup(process, cmd_args, timeout=timeout, strict_proc_matching=strict_proc_matching):
            raise AssertionError(f"Timed out waiting for process '{_describe(self, process)}' to start")

    def assertWaitForShutdown(self, process: Any = None, cmd_args: Any = None, *, timeout: float = 10,
                              strict_proc_matching: bool = True) -> None:
        if not self.waitForShutdown(process, cmd_args, timeout=timeout, strict_proc_matching=strict_proc_matching):
            raise AssertionError(f"Timed out waiting for process '{_describe(self, process)}' to finish")

