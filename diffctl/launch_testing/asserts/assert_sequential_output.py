"""Asserting that a process printed texts in a given order (PYTEST_DONT_REWRITE)."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from ..util import resolveProcesses

_CONTEXT_LINES = 3  # line ends walked over on each side of the last match, for a failure's excerpt


class SequentialTextChecker:
    """Finds texts one after the other in a list of output chunks (each chunk one or more lines); a failed
    search leaves the position where the last success put it."""

    def __init__(self, output: list[str]) -> None:
        self._output = output
        self._chunk = 0  # the chunk the next search starts in
        self._offset = 0  # and where in it

    def assertInText(self, msg: str) -> None:
        self.assertInStdout(msg)

    def assertInStdout(self, msg: str) -> None:
        offset = self._offset
        for chunk in range(self._chunk, len(self._output)):
            at = self._output[chunk].find(msg, offset)
            if at >= 0:
                self._chunk, self._offset = chunk, at + len(msg)
                return
            offset = 0
        raise AssertionError(
            f"'{msg}' not found in sequence after previous match.  The output near the last matched line:\n"
            f"{self.get_nearby_lines()}"
        )

    def get_nearby_lines(self) -> str:
        """The lines around the position of the last match: from a couple of chunks before it to a few after,
        cut at the third line end on either side."""
        first = max(0, self._chunk - 2)
        window = "".join(self._output[first:self._chunk + 4])
        here = self._offset + sum(len(c) for c in self._output[first:self._chunk])
        start = here
        for _ in range(_CONTEXT_LINES):
            start = max(window.rfind("\n", 0, start), 0)
        if start:
            start += 1  # the text after that line end
        end = here
        for _ in range(_CONTEXT_LINES):
            end = max(window.find("\n", end + 1), end)
        return window[start:end]


@contextmanager
def assertSequentialStdout(proc_output: Any, process: Any, cmd_args: Any = None) -> Iterator[SequentialTextChecker]:
    """`with assertSequentialStdout(proc_output, proc) as cm:` then `cm.assertInStdout(text)` for each text in
    the order the process must have printed them. One process only: output of several has no order."""
    action = resolveProcesses(proc_output, process=process, cmd_args=cmd_args, strict_proc_matching=True)[0]
    yield SequentialTextChecker([event.text.decode() for event in proc_output[action]])
