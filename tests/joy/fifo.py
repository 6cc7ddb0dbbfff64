"""A joystick made of a FIFO: the test writes `struct js_event` records (the kernel's joystick API) into it."""

from __future__ import annotations

import errno
import os
import time
from pathlib import Path

from diffctl.joy.linux_joystick import JS_EVENT_AXIS, JS_EVENT_BUTTON, JS_EVENT_INIT, pack_events

BUTTON, AXIS, INIT = JS_EVENT_BUTTON, JS_EVENT_AXIS, JS_EVENT_INIT


def make(path: Path) -> Path:
    os.mkfifo(path)
    return path


def open_writer(path: Path, alive, timeout_s: float = 60.0) -> int:
    """The FIFO's write end, once the node under test has opened it for reading (`alive()`: it still runs)."""
    deadline = time.monotonic() + timeout_s
    while True:
        try:
            return os.open(path, os.O_WRONLY | os.O_NONBLOCK)
        except OSError as e:
            if e.errno != errno.ENXIO or time.monotonic() > deadline or not alive():
                raise
        time.sleep(0.05)


def initial_state(buttons: int, axes: list[int]) -> list[tuple[int, int, int]]:
    """What the kernel sends on open: every button and axis, flagged JS_EVENT_INIT."""
    return [(BUTTON | INIT, n, 0) for n in range(buttons)] + [(AXIS | INIT, n, v) for n, v in enumerate(axes)]


def write(fd: int, *events: tuple[int, int, int]) -> None:
    os.write(fd, pack_events(events))
