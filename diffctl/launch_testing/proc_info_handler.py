"""proc_info: the last ProcessStarted or ProcessExited event of every process of a launch.

ProcInfoHandler is the plain record; ActiveProcInfoHandler is its thread-safe wrapper that tests use while
the launch runs, to wait for a process to start or to end (PYTEST_DONT_REWRITE).
"""

from __future__ import annotations

import threading
from collections.abc import Iterator
from typing import Any

from diffctl.launch.events.process import ProcessExited

from .util import NoMatchingProcessException, resolveProcesses


class ProcInfoHandler:
    """The latest start or exit event of each process, keyed by its action."""

    def __init__(self) -> None:
        self._proc_info: dict[Any, Any] = {}

    def append(self, process_info: Any) -> None:
        self._proc_info[process_info.action] = process_info

    def __iter__(self) -> Iterator[Any]:
        return iter(self._proc_info.values())

    def processes(self) -> Any:
        """The actions (ExecuteProcess) of every process seen."""
        return self._proc_info.keys()

    def process_names(self) -> list[str]:
        return [action.process_details["name"] for action in self._proc_info]

    def __getitem__(self, key: Any) -> Any:
        """The event of a process given by its action, or of the first whose name contains the string `key`."""
        if not isinstance(key, str):
            return self._proc_info[key]
        for action, event in self._proc_info.items():
            if key in action.process_details["name"]:
                return event
        raise KeyError(key)


class ActiveProcInfoHandler:
    """proc_info while the launch runs: thread-safe, with waits for a process's start and exit."""

    def __init__(self) -> None:
        self._sync_lock = threading.Condition()
        self._proc_info_handler = ProcInfoHandler()

    @property
    def proc_event(self) -> threading.Condition:
        """Notified at every new event (ProcessProxy.wait_for_shutdown waits on it)."""
        return self._sync_lock

    def append(self, process_info: Any) -> None:
        with self._sync_lock:
            self._proc_info_handler.append(process_info)
            self._sync_lock.notify_all()

    def __iter__(self) -> Iterator[Any]:
        with self._sync_lock:
            return iter(list(self._proc_info_handler))

    def processes(self) -> list[Any]:
        with self._sync_lock:
            return list(self._proc_info_handler.processes())

    def process_names(self) -> list[str]:
        with self._sync_lock:
            return list(self._proc_info_handler.process_names())

    def __getitem__(self, key: Any) -> Any:
        with self._sync_lock:
            return self._proc_info_handler[key]

    def _matching(self, process: Any, cmd_args: Any) -> list[Any]:
        try:
            return resolveProcesses(self._proc_info_handler, process=process, cmd_args=cmd_args,
                                    strict_proc_matching=True)
        except NoMatchingProcessException:
            return []

    def assertWaitForShutdown(self, process: Any, cmd_args: Any = None, *, timeout: float = 10) -> None:
        """Wait until the process has exited; fail the test at the timeout."""

        def exited() -> bool:
            found = self._matching(process, cmd_args)
            return bool(found) and isinstance(self._proc_info_handler[found[0]], ProcessExited)

        with self._sync_lock:
            if not self._sync_lock.wait_for(exited, timeout=timeout):
                raise AssertionError(f"Timed out waiting for process '{process}' to finish")

    def assertWaitForStartup(self, process: Any, cmd_args: Any = None, *, timeout: float = 10) -> None:
        """Wait until the process has started; fail the test at the timeout."""
        with self._sync_lock:
            if not self._sync_lock.wait_for(lambda: bool(self._matching(process, cmd_args)), timeout=timeout):
                raise AssertionError(f"Timed out waiting for process '{process}' to start")
