"""A process's output on its way to events and log lines.

`HeldBack` holds the chunks read before the start was reported, so that no output event comes before
ProcessStarted. `LineLog` cuts a stream into lines for the output loggers, keeping an unfinished line
until its end arrives (and, with `cached_output`, the whole text for `get_stdout()`).
"""

from __future__ import annotations

import os
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from ..events.process.process_stderr import ProcessStderr
from ..events.process.process_stdout import ProcessStdout

if TYPE_CHECKING:
    from ..launch_context import LaunchContext


class HeldBack:
    """The spawner's output sink: ProcessStdout / ProcessStderr events, released once `release()` is called."""

    def __init__(self, context: LaunchContext, details: dict[str, Any]) -> None:
        self._context = context
        self._details = details
        self._waiting: list[tuple[type, bytes]] | None = []

    def _emit(self, kind: type, data: bytes) -> None:
        self._context.emit_event_sync(kind(text=data, **self._details))

    def release(self) -> None:
        waiting, self._waiting = self._waiting or [], None
        for kind, data in waiting:
            self._emit(kind, data)

    def _take(self, kind: type, data: bytes) -> None:
        if self._waiting is None:
            self._emit(kind, data)
        else:
            self._waiting.append((kind, data))

    def on_stdout(self, data: bytes) -> None:
        self._take(ProcessStdout, data)

    def on_stderr(self, data: bytes) -> None:
        self._take(ProcessStderr, data)


class LineLog:
    """One stream's text, written to `write` a line at a time."""

    def __init__(self, keep_all: bool) -> None:
        self.keep_all = keep_all
        self.text = ''  # everything (keep_all), else the unfinished line
        self._written = 0  # keep_all: where the next line to write begins
        self._over = False  # the process ended for good: chunks go out as they come

    def add(self, chunk: str, write: Callable[[str], None]) -> None:
        if self._over and not self.keep_all:
            write(chunk)
            return
        self.text += chunk
        begin = self._written if self.keep_all else 0
        cut = self.text.rfind(os.linesep, begin)
        if cut < 0:
            return  # no line is complete yet
        for line in self.text[begin:cut].split(os.linesep):
            write(line)
        after = cut + len(os.linesep)
        if self.keep_all:
            self._written = after
        else:
            self.text = self.text[after:]

    def flush(self, write: Callable[[str], None], *, final: bool) -> None:
        """Write what is left of an unfinished line; `final`: no respawn will add to this stream."""
        if self.keep_all:
            for line in self.text[self._written:].splitlines(keepends=True):
                write(line)
            self._written = len(self.text)
            return
        if self.text:
            write(self.text)
            self.text = ''
        if final:
            self._over = True
