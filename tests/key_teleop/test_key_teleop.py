"""key_teleop (teleop_tools 2.0.0, Jazzy): the held-key rule of key_teleop.py (a key counts for 0.4 s after its
last report, forward_rate/backward_rate/rotation_rate), and the program in a pseudo-terminal drawn by curses,
driving key_vel on a real router with the arrow keys' escape sequences."""

from __future__ import annotations

import fcntl
import os
import struct
import sys
import termios
import time

import pytest

from diffctl.key_teleop.held_keys import DOWN, LEFT, RIGHT, UP, Rates, velocity
from tests.probe import Probe
from tests.teleop.test_keyboard_pty import Pty, wait_for

MS = 1_000_000


def test_held_keys_and_rates() -> None:
    rates = Rates()
    assert velocity({UP: 0}, 399 * MS, rates) == (0.8, 0.0)
    assert velocity({UP: 0}, 400 * MS, rates) == (0.0, 0.0)  # released: no report for 0.4 s
    assert velocity({DOWN: 0, LEFT: 0}, 100 * MS, rates) == (-0.5, 1.0)
    assert velocity({UP: 0, DOWN: 0, RIGHT: 0}, 0, Rates(1.2, 0.3, 2.0)) == (0.0, -2.0)


@pytest.mark.slow
def test_arrows_drive_key_vel_in_a_terminal(router: str, procs) -> None:
    probe = Probe("key_teleop_probe")
    got: list[object] = []
    probe.create_subscription("/key_vel", "geometry_msgs/msg/TwistStamped", got.append)
    pty = Pty()
    fcntl.ioctl(pty.slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 80, 0, 0))
    try:
        proc = procs.start([sys.executable, "-m", "diffctl", "run", "key_teleop", "key_teleop", "--ros-args",
                            "-p", "forward_rate:=0.6"], stdin=pty.slave, stdout=pty.slave, stderr=pty.slave,
                           env={**os.environ, "TERM": "xterm"})
        assert wait_for(lambda: len(got) >= 3, pty, timeout_s=60), pty.text  # zeros at hz
        assert (got[-1].twist.linear.x, got[-1].twist.angular.z, got[-1].header.frame_id) == (0.0, 0.0, "key_teleop")
        assert "Use arrow keys to move, q to exit." in pty.text

        def hold(sequence: str, linear: float, angular: float) -> None:
            # a held key: the terminal repeats it; keypad mode sends ESC O A/B/C/D
            deadline = time.monotonic() + 30
            while time.monotonic() < deadline:
                pty.type(sequence)
                pty.pump()
                if got and (got[-1].twist.linear.x, got[-1].twist.angular.z) == (linear, angular):
                    return
                time.sleep(0.05)
            raise AssertionError(f"no ({linear}, {angular}) for {sequence!r}; last {got[-1].twist}")

        hold("\x1bOA", 0.6, 0.0)
        assert wait_for(lambda: "Linear: 0.600000, Angular: 0.000000" in pty.text, pty), pty.text
        hold("\x1bOA\x1bOD", 0.6, 1.0)
        assert wait_for(lambda: (got[-1].twist.linear.x, got[-1].twist.angular.z) == (0.0, 0.0), pty)  # let go
        pty.type("q")
        assert proc.wait(15) == 0
    finally:
        probe.close()
        pty.close()
