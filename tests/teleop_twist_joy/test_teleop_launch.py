"""The game pad path end to end, real processes on a real router, a joystick made of a FIFO of js_event
records: the tutorial's `diffctl launch teleop …` line (launch/teleop.yaml, upstream's teleop-launch.py: joy_node
with deadzone 0.3, teleop_node with the xbox preset) and `diffctl teleop joy` drive /diffbot_base_controller/cmd_vel
with TwistStamped as teleop_twist_joy computes it, and stop with one zero command."""

from __future__ import annotations

import os
import threading
from pathlib import Path
from typing import Any

import pytest

from tests.joy import fifo
from tests.joy.fifo import AXIS, BUTTON
from tests.probe import parameters, probe
from tests.waiting import wait_for

pytestmark = pytest.mark.slow
TOPIC = "/diffbot_base_controller/cmd_vel"
# xbox.config.yaml: axis 1 forward at 0.7, axis 0 yaw at 0.4, enable button 2; joy_node's deadzone 0.3
FORWARD, RIGHT = -16000, 24000  # raw stick values (up is negative on Linux)
DEAD = 0.3 * 32767


def expected(raw: int, scale: float) -> float:
    return scale * -(raw - DEAD if raw > 0 else raw + DEAD) / (0.7 * 32767)


BOOL, INTEGER, DOUBLE, STRING = 1, 2, 3, 4
# What joy.cpp and teleop_twist_joy.cpp declare (their defaults' types), besides rclcpp's own parameters
JOY_NODE = {"device_id": INTEGER, "device_name": STRING, "deadzone": DOUBLE, "autorepeat_rate": DOUBLE,
            "sticky_buttons": BOOL, "coalesce_interval_ms": INTEGER}
TELEOP_NODE = {"publish_stamped_twist": BOOL, "frame": STRING, "require_enable_button": BOOL,
               "enable_button": INTEGER, "enable_turbo_button": INTEGER, "inverted_reverse": BOOL,
               **{f"axis_{k}.{f}": INTEGER for k, fs in (("linear", "xyz"), ("angular", ("yaw", "pitch", "roll")))
                  for f in fs},
               **{f"scale_{k}{t}.{f}": DOUBLE for k, fs in (("linear", "xyz"), ("angular", ("yaw", "pitch", "roll")))
                  for t in ("", "_turbo") for f in fs}}


def drive(procs, argv: list[str], js: Path, declared: bool = False) -> list[Any]:
    p = probe("teleop_probe")
    lock = threading.Lock()
    got: list[Any] = []

    def on(m: Any) -> None:
        with lock:
            got.append(m)

    p.create_subscription(TOPIC, "geometry_msgs/msg/TwistStamped", on)
    proc = procs.diffctl(*argv, env={**os.environ, "SDL_JOYSTICK_DEVICE": str(js)})
    fd = None
    try:
        fd = fifo.open_writer(js, lambda: proc.poll() is None)
        fifo.write(fd, *fifo.initial_state(11, [0] * 8))
        assert wait_for(lambda: bool(p.graph.publishers(TOPIC)), timeout_s=60)
        # Both ends of /joy up: the stick and button below reach teleop_node (joy_node autorepeats the state).
        # Not its one stop command on the first /joy message: sent once, it may go before this probe is matched.
        assert wait_for(lambda: any(e.node_fqn == "/teleop_twist_joy_node" for e in p.graph.subscribers("/joy"))
                        and any(e.node_fqn == "/joy_node" for e in p.graph.publishers("/joy")), timeout_s=60), (
            procs.stop(proc), proc.stdout.read())
        if declared:
            for node, table in (("/joy_node", JOY_NODE), ("/teleop_twist_joy_node", TELEOP_NODE)):
                found = {name: d.type for name, d in parameters(p, node).items() if name in table}
                assert found == table, node
        fifo.write(fd, (BUTTON, 2, 1), (AXIS, 1, FORWARD), (AXIS, 0, RIGHT))
        assert wait_for(lambda: any(m.twist.linear.x > 0.1 for m in list(got)), timeout_s=30)
        fifo.write(fd, (BUTTON, 2, 0))
        assert wait_for(lambda: got[-1].twist.linear.x == 0.0, timeout_s=30)
        with lock:
            return list(got)
    finally:
        if fd is not None:
            os.close(fd)
        p.close()
        assert procs.stop(proc) == 0


def check(got: list[Any]) -> None:
    assert all(m.header.frame_id == "teleop_twist_joy" for m in got)
    last = max(i for i, m in enumerate(got) if m.twist.linear.x != 0.0)
    m = got[last].twist
    assert m.linear.x == pytest.approx(expected(FORWARD, 0.7), rel=1e-6)
    assert m.angular.z == pytest.approx(expected(RIGHT, 0.4), rel=1e-6) and m.angular.z < 0  # right turn
    assert len(got) == last + 2 and got[-1].twist.angular.z == 0.0  # released: one zero, then silence


def test_tutorial_launch_line_drives_the_controller(router: str, procs, tmp_path: Path) -> None:
    check(drive(procs, ["launch", "teleop", "joy_config:=xbox", "publish_stamped_twist:=true", f"joy_vel:={TOPIC}"],
                fifo.make(tmp_path / "js"), declared=True))


def test_teleop_joy_command_drives_the_controller(router: str, procs, tmp_path: Path) -> None:
    js = fifo.make(tmp_path / "pad")
    check(drive(procs, ["teleop", "joy", "--device", str(js), "--joy-config", "xbox"], js))
