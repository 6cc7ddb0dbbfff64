"""proc_output: the output events of a launch's processes, kept in arrival order and per process name.

IoHandler is the plain record (what post-shutdown tests get); ActiveIoHandler wraps one behind a condition
variable so the launch thread appends while a test thread reads and waits for text (PYTEST_DONT_REWRITE).
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterator
from typing import Any

from .util import NoMatchingProcessException, resolveProcesses


class IoHandler:
    """Every ProcessIO event of a launch, in order, and grouped by the name of the process it came from."""

    def __init__(self) -> None:
        self._events: list[Any] = []
        self._by_name: dict[str, list[Any]] = {}

    def track(self, process_name: str) -> None:
        """A process started: it is known by name before it prints anything."""
        self._by_name.setdefault(process_name, [])

    def append(self, process_io: Any) -> None:
        self._events.append(process_io)
        self._by_name.setdefault(process_io.process_name, []).append(process_io)

    def __iter__(self) -> Iterator[Any]:
        return iter(self._events)

    def processes(self) -> list[Any]:
        """The actions (ExecuteProcess) of the processes that printed something."""
        return [events[0].action for events in self._by_name.values() if events]

    def process_names(self) -> Any:
        """The names of every process started or heard from."""
        return self._by_name.keys()

    def __getitem__(self, key: Any) -> list[Any]:
        """The output events of a process, given by name or by its action."""
        name = key if isinstance(key, str) else key.process_details["name"]
        return list(self._by_name[name])


class ActiveIoHandler:
    """proc_output while the launch runs: thread-safe, and tests can wait for output to appear."""

    def __init__(self) -> None:
        self._sync_lock = threading.Condition()
        self._io_handler = IoHandler()

    @property
    def io_event(self) -> threading.Condition:
        """Notified at every new event (ProcessProxy.wait_for_output waits on it)."""
        return self._sync_lock

    def track(self, process_name: str) -> None:
        with self._sync_lock:
            self._io_handler.track(process_name)
            self._sync_lock.notify_all()

    def append(self, process_io: Any) -> None:
        with self._sync_lock:
            self._io_handler.append(process_io)
            self._sync_lock.notify_all()

    def __iter__(self) -> Iterator[Any]:
        with self._sync_lock:
            return iter(list(self._io_handler))

    def processes(self) -> list[Any]:
        with self._sync_lock:
            return list(self._io_handler.processes())

    def process_names(self) -> list[str]:
        with self._sync_lock:
            return list(self._io_handler.process_names())

    def __getitem__(self, key: Any) -> list[Any]:
        with self._sync_lock:
            return self._io_handler[key]

    def waitFor(self, expected_output: Any, process: Any = None, cmd_args: Any = None, *,
                strict_proc_matching: bool = True, output_filter: Callable[[str], str] | None = None,
                timeout: float = 10, strip_ansi_escape_sequences: bool = True, stream: str = "stderr") -> bool:
        """Wait until `expected_output` is in `stream` of `process` (any process by default); False at the
        timeout. A process name that matches nothing at the timeout raises instead."""
        from .asserts.assert_output import assertInStream  # here: asserts and tools import this module

        def found() -> bool:
            try:
                assertInStream(self._io_handler, expected_output, process, cmd_args, output_filter=output_filter,
                               strict_proc_matching=strict_proc_matching,
                               strip_ansi_escape_sequences=strip_ansi_escape_sequences, stream=stream)
            except (NoMatchingProcessException, AssertionError):
                return False  # nothing printed yet, or not that
            return True

        with self._sync_lock:
            success = self._sync_lock.wait_for(found, timeout=timeout)
        # a name that never matched anything is more likely a typo than a slow process: say so
        if not success and not resolveProcesses(self, process=process, cmd_args=cmd_args, strict_proc_matching=False):
            raise Exception(
                f"After timeout, found no processes matching '{process}'  It either doesn't exist, was "
                "never launched, or didn't generate any output"
            )
        return success

    def assertWaitFor(self, *args: Any, **kwargs: Any) -> None:
        """waitFor, failing the test at the timeout."""
        if not self.waitFor(*args, **kwargs):
            raise AssertionError("Waiting for output timed out")
