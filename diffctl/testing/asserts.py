"""launch_testing.asserts: exit codes and output of the processes of a launch test.

Messages are launch_testing's, so a CI log reads as it would under `launch_test`.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

from diffctl.testing.handlers import output_matches, strip_ansi
from diffctl.testing.proc_lookup import process_name, resolve_processes

EXIT_OK = 0
EXIT_SIGINT = 130
EXIT_SIGQUIT = 131
EXIT_SIGKILL = 137
EXIT_SIGSEGV = 139
EXIT_FORCED = 1


def assertExitCodes(
    proc_info: Any,
    allowable_exit_codes: list[int] | tuple[int, ...] = (EXIT_OK,),
    process: Any = None,
    cmd_args: Any = None,
    *,
    strict_proc_matching: bool = True,
) -> None:
    """Every matching process has exited with one of `allowable_exit_codes`."""
    for action in resolve_processes(proc_info, process, cmd_args, strict_proc_matching=strict_proc_matching):
        info = proc_info[action]
        code = getattr(info, "returncode", None)
        if code is None:
            raise AssertionError(f"Proc {process_name(action)} is still running: it has not exited yet")
        if code not in allowable_exit_codes:
            raise AssertionError(f"Proc {process_name(action)} exited with code {code}")


def assertDefaultStream() -> str:
    return "stderr"


def assertInStream(
    proc_output: Any,
    expected_output: Any,
    process: Any = None,
    cmd_args: Any = None,
    *,
    output_filter: Callable[[str], str] | None = None,
    strict_proc_matching: bool = True,
    strip_ansi_escape_sequences: bool = True,
    stream: str = "stderr",
) -> None:
    names = []
    for action in resolve_processes(proc_output, process, cmd_args, strict_proc_matching=strict_proc_matching):
        names.append(process_name(action))
        try:
            text = proc_output.text(
                action, stream, strip_ansi_escape_sequences=strip_ansi_escape_sequences, output_filter=output_filter
            )
        except KeyError:
            continue
        if output_matches(text, expected_output):
            return
    raise AssertionError(
        f"Did not find '{expected_output}' in output for any of the matching processes: {', '.join(names)}"
    )


def assertInStdout(proc_output: Any, expected_output: Any, process: Any = None, cmd_args: Any = None,
                   **kw: Any) -> None:
    assertInStream(proc_output, expected_output, process, cmd_args, stream="stdout", **kw)


def assertInStderr(proc_output: Any, expected_output: Any, process: Any = None, cmd_args: Any = None,
                   **kw: Any) -> None:
    assertInStream(proc_output, expected_output, process, cmd_args, stream="stderr", **kw)


class SequentialTextChecker:
    """Substrings that must appear in order through a process's output chunks (each a line here)."""

    def __init__(self, chunks: list[str]) -> None:
        self._chunks = chunks
        self._chunk = 0
        self._at = 0

    def assertInText(self, msg: str) -> None:
        for i in range(self._chunk, len(self._chunks)):
            start = self._at if i == self._chunk else 0
            at = self._chunks[i].find(msg, start)
            if at >= 0:
                self._chunk, self._at = i, at + len(msg)
                return
        near = self._chunks[max(0, self._chunk - 2): self._chunk + 3]
        raise AssertionError(
            f"'{msg}' not found in sequence after previous match.  The output near the last matched line:\n"
            + "".join(f"  {line}" if line.endswith("\n") else f"  {line}\n" for line in near)
        )

    assertInStdout = assertInText


@contextmanager
def assertSequentialStdout(proc_output: Any, process: Any, cmd_args: Any = None) -> Iterator[SequentialTextChecker]:
    """`with assertSequentialStdout(proc_output, proc) as cm: cm.assertInStdout('a'); cm.assertInStdout('b')`."""
    action = resolve_processes(proc_output, process, cmd_args)[0]
    chunks = [strip_ansi(e.text.decode(errors="replace")) for e in proc_output[action]]
    yield SequentialTextChecker(chunks)


__all__ = [
    "EXIT_FORCED",
    "EXIT_OK",
    "EXIT_SIGINT",
    "EXIT_SIGKILL",
    "EXIT_SIGQUIT",
    "EXIT_SIGSEGV",
    "assertDefaultStream",
    "assertExitCodes",
    "assertInStderr",
    "assertInStdout",
    "assertInStream",
    "assertSequentialStdout",
]
