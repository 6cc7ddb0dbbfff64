"""The product as a user meets it: `diffctl launch sim_control` headless at rtf:=0, driven over the bus.

Distances and angles are measured at steady state over 2 s of sim time (the tutorial's controller YAML
limits acceleration to 1 m/s² and 1 rad/s², so the first half second is a ramp): from the first odometry
sample at the commanded speed, with samples picked by their sim-time stamps, so the results do not depend
on how fast this machine runs the simulation.
"""

from __future__ import annotations

import math
import signal
import time
from pathlib import Path

import pytest

from tests.e2e.stack import Stack

pytestmark = pytest.mark.slow
SEC = 1_000_000_000
CMD = "/diffbot_base_controller/cmd_vel"
TWIST_STAMPED = "geometry_msgs/msg/TwistStamped"


def drive_steady(stack: Stack, topic: str, typename: str, values: dict, target: tuple[int, float],
                 measure_s: float = 2.0) -> tuple[int, int]:
    """Command `values` on every sim tick until odometry reports the target speed, then measure `measure_s`.

    `target` is (index into the odometry sample's (x, y, yaw, vx, wz), value). Returns the sim-time window.
    """
    stack.command(topic, typename, values)
    index, value = target
    deadline = stack.clock_ns + 30 * SEC
    while True:
        last = stack.watch.last(stack.watch.odom)
        if last is not None and abs(last.value[index] - value) <= max(0.01 * abs(value), 0.005):
            break
        assert stack.clock_ns < deadline, f"odometry never reached {value} (last: {last})"
        stack.wait_sim(stack.clock_ns + SEC // 100)
    start = last.t_ns
    stack.wait_sim(start + int(measure_s * SEC) + SEC // 5)  # a little past the end so odom has a sample there
    return start, start + int(measure_s * SEC)


def check_stack(stack: Stack, odom_topic: str, cmd_topic: str, cmd_type: str, stamped: bool,
                brakes_on_timeout: bool = True, joint_states_hz: float = 20.0) -> None:
    w = stack.watch

    def cmd(vx: float, wz: float) -> dict:
        twist = {"linear": {"x": vx}, "angular": {"z": wz}}
        return {"twist": twist} if stamped else twist

    stack.wait_sim(stack.clock_ns + SEC // 2)
    # --- straight: 0.5 m/s for 2 s of sim time → 1.0 m ± 5 %
    t0, t1 = drive_steady(stack, cmd_topic, cmd_type, cmd(0.5, 0.0), (3, 0.5))
    a, b = w.at(w.odom, t0), w.at(w.odom, t1)
    # Samples this busy test process missed would shift the ends: scale to exactly 2 s between the stamps.
    travelled = math.hypot(b.value[0] - a.value[0], b.value[1] - a.value[1]) * 2 * SEC / (b.t_ns - a.t_ns)
    assert travelled == pytest.approx(1.0, rel=0.05), f"odometry travelled {travelled:.4f} m in 2 s at 0.5 m/s"
    # ground truth and odometry agree (both measured from the spawn point)
    g0, g1 = w.truth[0], w.at(w.truth, b.t_ns)
    truth_moved = math.hypot(g1.value[0] - g0.value[0], g1.value[1] - g0.value[1])
    odom_moved = math.hypot(b.value[0], b.value[1])
    assert abs(truth_moved - odom_moved) < 0.03, f"ground truth {truth_moved:.4f} m vs odometry {odom_moved:.4f} m"

    # --- turn in place: 0.5 rad/s for 2 s → 1.0 rad ± 5 %
    t0, t1 = drive_steady(stack, cmd_topic, cmd_type, cmd(0.0, 0.5), (4, 0.5))
    a, b = w.at(w.odom, t0), w.at(w.odom, t1)
    turned = math.remainder(b.value[2] - a.value[2], math.tau) * 2 * SEC / (b.t_ns - a.t_ns)
    assert turned == pytest.approx(1.0, rel=0.05), f"odometry turned {turned:.4f} rad in 2 s at 0.5 rad/s"
    ga, gb = w.at(w.truth, a.t_ns), w.at(w.truth, b.t_ns)
    gt_turned = math.remainder(gb.value[2] - ga.value[2], math.tau) * 2 * SEC / (gb.t_ns - ga.t_ns)
    assert gt_turned == pytest.approx(turned, abs=0.05)

    if brakes_on_timeout:
        # --- stop publishing: the controller brakes within cmd_vel_timeout (0.5 s) plus its deceleration ramp
        stack.command(cmd_topic, cmd_type, None)
        last = stack.last_cmd_ns
        stack.wait_sim(last + 2 * SEC)
        # The last command is stamped `last`: the controller's timeout counts from that stamp.
        before_timeout = w.at(w.odom, last + int(0.45 * SEC)).value[4]
        braking = w.at(w.odom, last + int(0.75 * SEC)).value[4]
        stopped = w.at(w.odom, last + int(1.3 * SEC)).value[4]
        assert before_timeout > 0.45, f"slowed to {before_timeout:.3f} rad/s before cmd_vel_timeout expired"
        assert braking < 0.4, f"still at {braking:.3f} rad/s 0.75 s after the last command: no braking"
        assert abs(stopped) < 0.02, f"still turning at {stopped:.3f} rad/s 1.3 s after the last command"
    else:
        # Gazebo's DiffDrive holds the last command (it has no timeout): a zero command stops the car.
        drive_steady(stack, cmd_topic, cmd_type, cmd(0.0, 0.0), (4, 0.0), measure_s=0.5)
        assert abs(w.last(w.odom).value[4]) < 0.02

    # --- topics flow at their rates (in sim time); bridged samples trail the controller's, so let them land
    time.sleep(0.5)
    end = stack.clock_ns - SEC
    start = end - 2 * SEC
    assert w.rate_hz("/clock", start, end) == pytest.approx(100, rel=0.15)
    assert w.rate_hz("/joint_states", start, end) == pytest.approx(joint_states_hz, rel=0.15)
    assert w.rate_hz("/scan", start, end) == pytest.approx(10, rel=0.15)
    assert w.rate_hz("/tf", start, end) >= 18
    assert w.rate_hz(odom_topic, start, end) >= 18


def stop_and_check_reaped(stack: Stack) -> None:
    kids = stack.descendants()
    assert len(kids) >= 3, [k.name() for k in kids]
    t0 = time.monotonic()
    code = stack.stop(signal.SIGINT)
    assert code == 0, stack.output()
    assert not stack.survivors(), f"left behind: {stack.survivors()}"
    assert time.monotonic() - t0 < 10


@pytest.mark.parametrize("launch_file", ["sim_control", "launch/sim_control.launch.py"])
def test_sim_control_drive_turn_brake_and_shutdown(launch_file: str, stack_env: str, tmp_path: Path) -> None:
    stack = Stack(launch_file, tmp_path)
    try:
        stack.connect()
        stack.watch_odom("/diffbot_base_controller/odom")
        stack.wait_controllers_active(("diffbot_base_controller", "joint_state_broadcaster"))
        check_stack(stack, "/diffbot_base_controller/odom", CMD, TWIST_STAMPED, stamped=True)
        stop_and_check_reaped(stack)
    finally:
        stack.kill()


def test_earlier_variant_sim_yaml_drives_through_the_bridge(stack_env: str, tmp_path: Path) -> None:
    stack = Stack("sim", tmp_path)
    try:
        stack.connect()
        stack.watch_odom("/odom")
        deadline = time.monotonic() + 90
        while not stack.watch.odom:
            assert time.monotonic() < deadline and stack.proc.poll() is None, stack.output()
            stack.descendants()
            time.sleep(0.05)
        check_stack(stack, "/odom", "/cmd_vel", "geometry_msgs/msg/Twist", stamped=False, brakes_on_timeout=False,
                    joint_states_hz=50.0)
        stop_and_check_reaped(stack)
    finally:
        stack.kill()
