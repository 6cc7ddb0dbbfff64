"""A test's handle on one process of the launch (ProcessProxy), and starting one from a test (launch_process)."""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator
from typing import Any

from diffctl.launch import LaunchDescription
from diffctl.launch.actions import ExecuteProcess
from diffctl.launch.events import IncludeLaunchDescription, matches_action
from diffctl.launch.events.process import ProcessExited, ProcessStarted, ShutdownProcess
from diffctl.launch.utilities import ensure_argument_type

from ..io_handler import ActiveIoHandler
from ..proc_info_handler import ActiveProcInfoHandler


class _Answer:
    """True or False, with the output it was decided on shown in its repr (an assert's message)."""

    def __init__(self, result: bool, output: str | None) -> None:
        self._result = result
        self._output = output

    def __bool__(self) -> bool:
        return self._result

    def __repr__(self) -> str:
        return f"<BoolWithText({self._result}): {self._output!r}>"


class ProcessProxy:
    """What a test sees of one ExecuteProcess: its output so far, whether it runs, its exit code."""

    def __init__(self, process_action: Any, proc_info: Any, proc_output: Any, *,
                 output_filter: Callable[[str], str] | None = None) -> None:
        ensure_argument_type(process_action, types=ExecuteProcess, argument_name="process_action")
        ensure_argument_type(proc_info, types=ActiveProcInfoHandler, argument_name="proc_info")
        ensure_argument_type(proc_output, types=ActiveIoHandler, argument_name="proc_output")
        if output_filter is not None and not callable(output_filter):
            raise TypeError(f"Expected 'output_filter' to be callable but got '{output_filter!r}'")
        self._process_action = process_action
        self._proc_info = proc_info
        self._proc_output = proc_output
        self._output_filter = output_filter

    @property
    def target_process_action(self) -> Any:
        return self._process_action

    def wait_for_shutdown(self, timeout: float | None = None) -> bool:
        """Wait until the process has exited (None: for ever); whether it did."""
        with self._proc_info.proc_event:
            return self._proc_info.proc_event.wait_for(lambda: self.terminated, timeout=timeout)

    def wait_for_output(self, condition: Callable[[str], bool] | None = None, timeout: float | None = None) -> Any:
        """Wait, while the process runs, until its output (stdout and stderr) satisfies `condition` (any
        output by default); the answer is truthy when it did."""
        if condition is None:
            condition = lambda output: True  # noqa: E731
        if not callable(condition):
            raise TypeError(f"Expected 'condition' to be callable but got '{condition!r}'")
        seen: list[str | None] = [None]

        def satisfied() -> bool:
            if not self.running:
                return False
            seen[0] = self.output
            return bool(condition(seen[0]))

        with self._proc_output.io_event:
            result = self._proc_output.io_event.wait_for(satisfied, timeout=timeout)
        return _Answer(result, seen[0])

    def _text(self, select: Callable[[Any], bool]) -> str:
        text = "".join(e.text.decode() for e in self._proc_output[self._process_action] if select(e))
        return self._output_filter(text) if self._output_filter is not None else text

    @property
    def stdout(self) -> str:
        return self._text(lambda e: e.from_stdout)

    @property
    def stderr(self) -> str:
        return self._text(lambda e: e.from_stderr)

    @property
    def output(self) -> str:
        return self._text(lambda e: True)

    def _event(self) -> Any:
        if self._process_action not in self._proc_info.processes():
            return None
        return self._proc_info[self._process_action]

    @property
    def running(self) -> bool:
        return isinstance(self._event(), ProcessStarted)

    @property
    def terminated(self) -> bool:
        return isinstance(self._event(), ProcessExited)

    @property
    def exit_code(self) -> int | None:
        return self._proc_info[self._process_action].returncode


@contextlib.contextmanager
def launch_process(launch_service: Any, process_action: Any, proc_info: Any, proc_output: Any,
                   **kwargs: Any) -> Iterator[ProcessProxy]:
    """Start `process_action` in the running launch and give a ProcessProxy of it; on leaving, the process is
    shut down if it has not ended. Keyword arguments go to ProcessProxy."""
    ensure_argument_type(process_action, types=ExecuteProcess, argument_name="process_action")
    launch_service.emit_event(
        event=IncludeLaunchDescription(launch_description=LaunchDescription([process_action]))
    )
    proxy = ProcessProxy(process_action, proc_info, proc_output, **kwargs)
    try:
        yield proxy
    finally:
        if not proxy.terminated:
            launch_service.emit_event(event=ShutdownProcess(process_matcher=matches_action(process_action)))
