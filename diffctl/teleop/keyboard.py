"""The keyboard teleop loop: a raw terminal, teleop_twist_keyboard's keys, a live status line, zero on exit."""

from __future__ import annotations

import os
import select
import termios
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TextIO

from diffctl.teleop.keyboard_bindings import HELP, KeyboardTeleop, split_keys
from diffctl.teleop.shutdown import stop_on_signals
from diffctl.teleop.twist_command import TwistCommand


@contextmanager
def raw_terminal(fd: int) -> Iterator[None]:
    """Keys arrive one by one, unechoed, Ctrl-C as a byte; output processing stays on so newlines work."""
    old = termios.tcgetattr(fd)
    new = termios.tcgetattr(fd)
    new[3] &= ~(termios.ICANON | termios.ECHO | termios.ISIG | termios.IEXTEN)
    new[6][termios.VMIN] = 1
    new[6][termios.VTIME] = 0
    termios.tcsetattr(fd, termios.TCSANOW, new)
    try:
        yield
    finally:
        termios.tcsetattr(fd, termios.TCSADRAIN, old)


def run_keyboard(
    teleop: KeyboardTeleop,
    command: TwistCommand,
    *,
    repeat_rate_hz: float,
    fd_in: int,
    out: TextIO,
    stop: threading.Event | None = None,
) -> None:
    """Read keys until Ctrl-C/Ctrl-D/a signal; publish on every key and, while moving, at `repeat_rate_hz`."""
    stop = stop or threading.Event()
    stop_on_signals(stop)
    kind = command.typename.rsplit("/", 1)[-1]
    out.write(HELP.format(topic=command.topic, kind=kind))
    period_s = 1.0 / repeat_rate_hz if repeat_rate_hz > 0 else None

    def show() -> None:
        out.write("\r\x1b[K" + teleop.status())
        out.flush()

    try:
        with raw_terminal(fd_in):
            show()
            next_repeat = time.monotonic() + (period_s or 0.0)
            while not stop.is_set():
                timeout = 0.25 if period_s is None else max(0.0, min(0.25, next_repeat - time.monotonic()))
                ready, _, _ = select.select([fd_in], [], [], timeout)
                if ready:
                    data = os.read(fd_in, 64)
                    if not data:
                        break  # the terminal went away
                    for key in split_keys(data.decode(errors="ignore")):
                        if not teleop.press(key):
                            stop.set()
                            break
                    if stop.is_set():
                        break
                    command.publish(*_split(teleop.velocity()))
                    show()
                    next_repeat = time.monotonic() + (period_s or 0.0)
                elif period_s is not None and time.monotonic() >= next_repeat:
                    # Keeps a controller's cmd_vel_timeout from stopping the robot between key repeats.
                    if any(teleop.velocity()):
                        command.publish(*_split(teleop.velocity()))
                    next_repeat = time.monotonic() + period_s
    finally:
        command.stop()
        out.write("\r\x1b[Kstopped: sent a zero command\n")
        out.flush()


def _split(v: tuple[float, float, float, float]) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
    x, y, z, th = v
    return (x, y, z), (0.0, 0.0, th)
