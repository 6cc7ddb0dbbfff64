"""Single keys from the terminal for `bag play` (SPACE, arrows), as ros2 bag play's keyboard handler.

Only when stdin is a terminal: the terminal goes to cbreak mode (no echo, no line buffering) and is
restored on exit, whatever happens. Without a terminal (launch files, pipes, tests) nothing is read.
"""

from __future__ import annotations

import os
import select
import sys
import threading
from collections.abc import Callable
from types import TracebackType

KEYS = {b" ": "space", b"\x1b[C": "right", b"\x1b[A": "up", b"\x1b[B": "down"}


def decode(data: bytes) -> list[str]:
    """Key names in a chunk read from the terminal (arrows arrive as 3-byte escape sequences)."""
    out = []
    i = 0
    while i < len(data):
        for seq, name in KEYS.items():
            if data.startswith(seq, i):
                out.append(name)
                i += len(seq)
                break
        else:
            i += 1
    return out


class TerminalKeys:
    def __init__(self, on_key: Callable[[str], None]) -> None:
        self.on_key = on_key
        self._fd = sys.stdin.fileno() if sys.stdin is not None and sys.stdin.isatty() else None
        self._saved: list | None = None
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None

    @property
    def active(self) -> bool:
        return self._fd is not None

    def __enter__(self) -> TerminalKeys:
        if self._fd is None:
            return self
        import termios
        import tty

        self._saved = termios.tcgetattr(self._fd)
        tty.setcbreak(self._fd)
        self._thread = threading.Thread(target=self._read, name="bag-keys", daemon=True)
        self._thread.start()
        return self

    def _read(self) -> None:
        assert self._fd is not None
        while not self._stop.is_set():
            ready, _, _ = select.select([self._fd], [], [], 0.2)
            if not ready:
                continue
            data = os.read(self._fd, 16)
            if not data:
                return
            for key in decode(data):
                self.on_key(key)

    def __exit__(self, et: type[BaseException] | None, e: BaseException | None, tb: TracebackType | None) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(1.0)
        if self._fd is not None and self._saved is not None:
            import termios

            termios.tcsetattr(self._fd, termios.TCSADRAIN, self._saved)
