"""launch_testing.tools and launch_testing.util: a process launched from a test, output filters, keep-alive.

`launch_process(launch_service, action, proc_info, proc_output)` starts `action` in the running launch and
yields a ProcessProxy; on leaving, the process is shut down if it still runs. Output filters drop lines by
prefix or pattern before a test matches output.
"""

from __future__ import annotations

import contextlib
import re
import sys
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path
from typing import Any

from diffctl.launch_legacy.actions import LaunchDescription
from diffctl.launch_legacy.event_actions import EmitEvent
from diffctl.launch_legacy.events import ShutdownProcess, matches_action
from diffctl.launch_legacy.process_actions import ExecuteProcess


def KeepAliveProc() -> ExecuteProcess:
    """A process that does nothing until it is stopped: keeps a launch whose processes all exit alive."""
    return ExecuteProcess(
        cmd=[sys.executable, "-c", "import signal\ntry:\n    signal.pause()\nexcept KeyboardInterrupt:\n    pass"],
        name="keep_alive",
    )


def basic_output_filter(
    filtered_prefixes: Iterable[str] | None = None, filtered_patterns: Iterable[str] | None = None
) -> Callable[[str], str]:
    """Drop every line that starts with one of `filtered_prefixes` or matches one of `filtered_patterns`."""
    prefixes = tuple(["pid", "rc"] if filtered_prefixes is None else filtered_prefixes)
    patterns = [re.compile(p) for p in (filtered_patterns or [])]

    def _filter(output: str) -> str:
        kept = []
        for line in output.splitlines(keepends=True):
            if prefixes and line.startswith(prefixes):
                continue
            if any(p.match(line.rstrip("\n")) for p in patterns):
                continue
            kept.append(line)
        return "".join(kept)

    return _filter


def expected_output_from_file(path: str) -> Any:
    """`path.txt` (lines to find in order) or `path.regex` (one regular expression)."""
    txt, regex = Path(path + ".txt"), Path(path + ".regex")
    if txt.is_file():
        return txt.read_text().splitlines()
    if regex.is_file():
        return re.compile(regex.read_text(), re.MULTILINE)
    raise RuntimeError(f"could not find {txt} nor {regex}")


def expect_output(text: str | None = None, expected_text: Any = None, *, lines: list[str] | None = None,
                  expected_lines: Any = None, strict: bool = False) -> bool:
    """Whether `text` (or `lines`) holds the expected text, lines (in order) or regex; `strict`: exactly."""
    if lines is None:
        lines = (text or "").splitlines()
    if text is None:
        text = "\n".join(lines)
    if expected_lines is not None:
        expected = list(expected_lines)
        if strict:
            return lines == expected
        at = 0
        for want in expected:
            while at < len(lines) and lines[at] != want:
                at += 1
            if at == len(lines):
                return False
            at += 1
        return True
    if isinstance(expected_text, re.Pattern):
        return (expected_text.fullmatch(text) if strict else expected_text.search(text)) is not None
    return text == expected_text if strict else str(expected_text) in text


class ProcessProxy:
    """What a test sees of one process: its output so far, whether it runs, its exit code; waits for both."""

    def __init__(self, process_action: Any, proc_info: Any, proc_output: Any, *,
                 output_filter: Callable[[str], str] | None = None) -> None:
        self._action = process_action
        self._proc_info = proc_info
        self._proc_output = proc_output
        self._output_filter = output_filter

    def _text(self, stream: str) -> str:
        try:
            return self._proc_output.text(self._action, stream, output_filter=self._output_filter)
        except KeyError:
            return ""

    @property
    def stdout(self) -> str:
        return self._text("stdout")

    @property
    def stderr(self) -> str:
        return self._text("stderr")

    @property
    def output(self) -> str:
        return self._text("both")

    @property
    def running(self) -> bool:
        try:
            return not hasattr(self._proc_info[self._action], "returncode")
        except KeyError:
            return False

    @property
    def terminated(self) -> bool:
        try:
            return hasattr(self._proc_info[self._action], "returncode")
        except KeyError:
            return False

    @property
    def exit_code(self) -> int | None:
        try:
            return getattr(self._proc_info[self._action], "returncode", None)
        except KeyError:
            return None

    def wait_for_shutdown(self, timeout: float | None = None) -> bool:
        return self._proc_info.waitForShutdown(process=self._action, timeout=10 if timeout is None else timeout)

    def wait_for_output(self, condition: Callable[[str], bool] | None = None, timeout: float | None = None,
                        stream: str = "stdout") -> bool:
        import time

        deadline = time.monotonic() + (10 if timeout is None else timeout)
        condition = condition or (lambda text: bool(text))
        with self._proc_output._lock:
            while True:
                if condition(self._text(stream)):
                    return True
                left = deadline - time.monotonic()
                if left <= 0:
                    return False
                self._proc_output._lock.wait(left)


@contextlib.contextmanager
def launch_process(launch_service: Any, process_action: Any, proc_info: Any, proc_output: Any,
                   **kwargs: Any) -> Iterator[ProcessProxy]:
    """Start `process_action` in the running launch; shut it down on leaving if it still runs."""
    launch_service.include_launch_description(LaunchDescription([process_action]))
    proxy = ProcessProxy(process_action, proc_info, proc_output, **kwargs)
    try:
        yield proxy
    finally:
        if proxy.running or not proxy.terminated:
            launch_service.include_launch_description(
                LaunchDescription([EmitEvent(event=ShutdownProcess(process_matcher=matches_action(process_action)))])
            )
