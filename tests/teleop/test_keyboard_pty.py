"""`diffctl teleop keyboard` in a pseudo-terminal, publishing on a real router, checked by a subscriber."""

from __future__ import annotations

import os
import select
import signal
import subprocess
import sys
import time
from collections.abc import Callable

import pytest

from tests.probe import Probe


class Pty:
    """The controlling side of a pseudo-terminal: type keys, collect what the program printed."""

    def __init__(self) -> None:
        self.master, self.slave = os.openpty()
        self.text = ""

    def pump(self) -> None:
        while select.select([self.master], [], [], 0)[0]:
            try:
                chunk = os.read(self.master, 4096)
            except OSError:  # EIO once the child closed the slave side
                return
            if not chunk:
                return
            self.text += chunk.decode(errors="replace")

    def type(self, keys: str) -> None:
        os.write(self.master, keys.encode())

    def close(self) -> None:
        for fd in (self.master, self.slave):
            try:
                os.close(fd)
            except OSError:
                pass


def wait_for(pred: Callable[[], bool], pty: Pty, timeout_s: float = 10.0) -> bool:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        pty.pump()
        if pred():
            return True
        time.sleep(0.02)
    return pred()


@pytest.mark.parametrize(
    ("args", "topic", "typename", "quit_with"),
    [
        ([], "/diffbot_base_controller/cmd_vel", "geometry_msgs/msg/TwistStamped", "ctrl-c"),
        (["--unstamped", "--topic", "/cmd_vel", "--speed", "0.2"], "/cmd_vel", "geometry_msgs/msg/Twist", "sigterm"),
    ],
)
def test_keys_drive_and_exit_sends_zero(
    router: str, procs, args: list[str], topic: str, typename: str, quit_with: str
) -> None:
    node = Probe("keyboard_probe")
    got: list[object] = []
    node.create_subscription(topic, typename, got.append)
    pty = Pty()
    try:
        proc = procs.start(
            [sys.executable, "-m", "diffctl", "teleop", "keyboard", "--repeat-rate", "0", *args],
            stdin=pty.slave,
            stdout=pty.slave,
            stderr=pty.slave,
        )
        assert wait_for(lambda: "speed " in pty.text, pty), pty.text
        assert wait_for(lambda: any(e.node == "teleop_twist_keyboard" for e in node.graph.publishers(topic)), pty)
        speed = float(args[args.index("--speed") + 1]) if "--speed" in args else 0.5

        def twist(i: int) -> object:
            return got[i].twist if typename.endswith("Stamped") else got[i]

        pty.type("i")
        assert wait_for(lambda: len(got) >= 1, pty), pty.text
        assert (twist(0).linear.x, twist(0).angular.z) == (speed, 0.0)
        if typename.endswith("Stamped"):
            assert got[0].header.stamp.sec > 0  # stamped with the node's clock, not zero
        pty.type("q")  # speeds +10 %, same direction
        assert wait_for(lambda: len(got) >= 2, pty)
        assert twist(1).linear.x == pytest.approx(speed * 1.1)
        pty.type("j")
        assert wait_for(lambda: len(got) >= 3, pty)
        assert (twist(2).linear.x, twist(2).angular.z) == (0.0, pytest.approx(1.1))
        assert wait_for(lambda: "turn 1.10" in pty.text, pty), pty.text  # the live status line
        if quit_with == "ctrl-c":
            pty.type("\x03")
        else:
            os.killpg(proc.pid, signal.SIGTERM)
        assert proc.wait(10) == 0
        assert wait_for(lambda: len(got) >= 4, pty)
        last = twist(len(got) - 1)
        assert (last.linear.x, last.angular.z) == (0.0, 0.0), "exit must leave the robot with a zero command"
        pty.pump()
        assert "sent a zero command" in pty.text
    finally:
        node.close()
        pty.close()


def test_not_a_terminal_is_a_clear_error() -> None:
    r = subprocess.run(
        [sys.executable, "-m", "diffctl", "teleop", "keyboard"],
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert r.returncode == 2 and "stdin is not one" in " ".join(r.stderr.split())


def test_ros_executable_keeps_upstream_defaults(router: str, procs) -> None:
    """teleop_twist_keyboard as Jazzy's (2.4.1): Twist on cmd_vel, speed/turn parameters, all read-only."""
    from tests.probe import parameters

    node = Probe("keyboard_probe")
    got: list[object] = []
    node.create_subscription("/cmd_vel", "geometry_msgs/msg/Twist", got.append)
    pty = Pty()
    try:
        proc = procs.start([sys.executable, "-m", "diffctl", "run", "teleop_twist_keyboard", "teleop_twist_keyboard",
                            "--ros-args", "-p", "speed:=0.3"], stdin=pty.slave, stdout=pty.slave, stderr=pty.slave)
        assert wait_for(lambda: any(e.node == "teleop_twist_keyboard" for e in node.graph.publishers("/cmd_vel")),
                        pty, timeout_s=60), pty.text
        described = parameters(node, "/teleop_twist_keyboard")
        assert {n: bool(d.read_only) for n, d in described.items() if n in ("stamped", "frame_id", "speed", "turn")} \
            == {"stamped": True, "frame_id": True, "speed": True, "turn": True}
        pty.type("u")
        assert wait_for(lambda: len(got) >= 1, pty), pty.text
        assert (got[0].linear.x, got[0].angular.z) == (0.3, 1.0)
        time.sleep(0.3)
        assert len(got) == 1  # on key presses only: no repeating
        pty.type("\x03")
        assert proc.wait(10) == 0
        assert wait_for(lambda: len(got) >= 2, pty)
        assert (got[-1].linear.x, got[-1].angular.z) == (0.0, 0.0)
    finally:
        node.close()
        pty.close()
    pty = Pty()
    try:  # as upstream raises: a frame without stamped messages is refused
        proc = procs.start([sys.executable, "-m", "diffctl", "run", "teleop_twist_keyboard", "teleop_twist_keyboard",
                            "--ros-args", "-p", "frame_id:=base_link"], stdin=pty.slave, stdout=pty.slave,
                           stderr=pty.slave)
        assert proc.wait(60) == 2
        assert wait_for(lambda: "'frame_id' can only be set when 'stamped' is True" in pty.text, pty), pty.text
    finally:
        pty.close()
