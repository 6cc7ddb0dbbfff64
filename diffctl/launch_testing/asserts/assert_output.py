"""Output assertions on proc_output: expected text in a process's stdout or stderr (PYTEST_DONT_REWRITE)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ..tools.output import remove_ansi_escape_sequences
from ..tools.text import build_text_match
from ..util import resolveProcesses

_STREAMS = {"stdout": "from_stdout", "stderr": "from_stderr"}


def assertInStream(proc_output: Any, expected_output: Any, process: Any, cmd_args: Any = None, *,
                   output_filter: Callable[[str], str] | None = None, strict_proc_matching: bool = True,
                   strip_ansi_escape_sequences: bool = True, stream: str = "stderr") -> None:
    """`expected_output` (a string, a regular expression, or a sequence of them in order) was printed on
    `stream` by the process `process` names (with several matches allowed, by any of them)."""
    processes = resolveProcesses(proc_output, process=process, cmd_args=cmd_args,
                                 strict_proc_matching=strict_proc_matching)
    if output_filter is not None and not callable(output_filter):
        raise ValueError("output_filter is not callable")
    if stream not in _STREAMS:
        raise ValueError("Invalid value for stream; must be 'stdout' or 'stderr'")
    match = build_text_match(expected_output)
    for action in processes:
        text = "".join(e.text.decode() for e in proc_output[action] if getattr(e, _STREAMS[stream]))
        if strip_ansi_escape_sequences:
            text = remove_ansi_escape_sequences(text)
        if output_filter is not None:
            text = output_filter(text)
        if match(text) is not None:
            return
    names = ", ".join(sorted(a.process_details["name"] for a in processes))
    raise AssertionError(f"Did not find '{expected_output}' in output for any of the matching processes: {names}")


def assertInStdout(proc_output: Any, expected_output: Any, process: Any, cmd_args: Any = None, *,
                   output_filter: Callable[[str], str] | None = None, strict_proc_matching: bool = True,
                   strip_ansi_escape_sequences: bool = True) -> None:
    """assertInStream on stdout."""
    assertInStream(proc_output, expected_output, process, cmd_args, output_filter=output_filter,
                   strict_proc_matching=strict_proc_matching,
                   strip_ansi_escape_sequences=strip_ansi_escape_sequences, stream="stdout")


def assertInStderr(proc_output: Any, expected_output: Any, process: Any, cmd_args: Any = None, *,
                   output_filter: Callable[[str], str] | None = None, strict_proc_matching: bool = True,
                   strip_ansi_escape_sequences: bool = True) -> None:
    """assertInStream on stderr."""
    assertInStream(proc_output, expected_output, process, cmd_args, output_filter=output_filter,
                   strict_proc_matching=strict_proc_matching,
                   strip_ansi_escape_sequences=strip_ansi_escape_sequences, stream="stderr")


def assertDefaultStream() -> str:
    """The stream assertInStream reads unless told: 'stderr' (since Foxy; Eloquent read stdout)."""
    return "stderr"
