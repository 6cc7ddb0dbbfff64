"""Polling for a condition in tests that watch real processes."""

from __future__ import annotations

import os
import select
import time
import weakref
from collections.abc import Callable
from typing import IO


def wait_for(pred: Callable[[], bool], timeout_s: float = 10.0, every: Callable[[], None] | None = None) -> bool:
    """Whether `pred()` became true within `timeout_s`; `every()` runs before each look (e.g. publish again)."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if every:
            every()
        if pred():
            return True
        time.sleep(0.05)
    return pred()


# What was read past the last line returned, per stream object (not per descriptor: a closed pipe's number is
# soon another child's, and its leftovers must not become that child's first lines).
_unread: weakref.WeakKeyDictionary[IO[str], bytes] = weakref.WeakKeyDictionary()


def lines_until(stream: IO[str], pred: Callable[[str], bool], timeout_s: float) -> tuple[list[str], bool]:
    """A child's output lines up to the first for which `pred` holds (True), or all that came by the timeout or
    the end (False). Read from the pipe's descriptor: a buffered `readline()` after `select` can keep a second
    line in its buffer where select no longer sees it, and the wait then outlasts any bound."""
    fd = stream.fileno()
    buf = _unread.pop(stream, b"")
    lines: list[str] = []
    deadline = time.monotonic() + timeout_s
    while True:
        while b"\n" in buf:
            raw, buf = buf.split(b"\n", 1)
            line = raw.decode("utf-8", "replace") + "\n"
            lines.append(line)
            if pred(line):
                _unread[stream] = buf
                return lines, True
        left = deadline - time.monotonic()
        ready, _, _ = select.select([fd], [], [], max(0.0, left)) if left > 0 else ([], [], [])
        chunk = os.read(fd, 65536) if ready else b""
        if not chunk:
            if buf:
                lines.append(buf.decode("utf-8", "replace"))
            return lines, False
        buf += chunk
