"""mecanum_drive_controller driven directly (a real client node), with the parameter files, references and expected
wheel speeds of upstream's test_mecanum_drive_controller.cpp (ros2_controllers jazzy): wheels_radius 0.5, lx + ly
1.0, reference_timeout 0.9; linear.x 1.5 → every wheel 3.0 rad/s."""

from __future__ import annotations

import math

import pytest
from controller_harness import NS, START_NS, activate, configure, hand_interfaces, make_controller, update

from diffctl.control.controllers.mecanum_drive_controller import MecanumDriveController
from diffctl.control.lifecycle import State
from diffctl.control.math.mecanum_kinematics import MecanumGeometry, body_twist, wheel_velocities_radps

pytestmark = pytest.mark.usefixtures("client_bus")

NAME = "test_mecanum_drive_controller"
WHEELS = {"front_left_wheel_command_joint_name": "front_left_wheel_joint",
          "front_right_wheel_command_joint_name": "front_right_wheel_joint",
          "rear_right_wheel_command_joint_name": "back_right_wheel_joint",
          "rear_left_wheel_command_joint_name": "back_left_wheel_joint"}
PARAMS = {"reference_timeout": 0.9, **WHEELS, "kinematics.wheels_radius": 0.5,
          "kinematics.sum_of_robot_center_projection_on_X_Y_axis": 1.0,
          "twist_covariance_diagonal": [0.0, 7.0, 14.0, 21.0, 28.0, 35.0],
          "pose_covariance_diagonal": [0.0, 6.0, 12.0, 18.0, 24.0, 30.0]}
LIMITS = {f"{axis}.{k}": v for axis in ("linear.x", "linear.y", "angular.z")
          for k, v in (("max_acceleration", 2.0), ("max_deceleration", -4.0), ("max_acceleration_reverse", -8.0),
                       ("max_deceleration_reverse", 10.0))}


def running(params=None, chained=False, namespace="/"):
    c = make_controller(MecanumDriveController, NAME, {**PARAMS, **(params or {})}, namespace=namespace)
    configure(c)
    cmd, state = hand_interfaces(c, {n: 111.0 for n in c.command_interface_configuration().names})
    if chained:
        c.set_chained_mode(True)
    activate(c)
    return c, list(cmd.values()), list(state.values())


def refs(c, x, y, z):
    c.reference_interfaces[0].value, c.reference_interfaces[1].value, c.reference_interfaces[2].value = x, y, z


def stamped(t_ns, x=1.5, y=0.0, z=0.0):
    return {"header": {"stamp": {"sec": t_ns // NS, "nanosec": t_ns % NS}},
            "twist": {"linear": {"x": x, "y": y}, "angular": {"z": z}}}


def test_interfaces_and_frames() -> None:
    c, _, _ = running()
    assert c.command_interface_configuration().names == [
        "front_left_wheel_joint/velocity", "front_right_wheel_joint/velocity", "back_right_wheel_joint/velocity",
        "back_left_wheel_joint/velocity"]
    assert [r.name for r in c.reference_interfaces] == [f"{NAME}/linear/x/velocity", f"{NAME}/linear/y/velocity",
                                                        f"{NAME}/angular/z/velocity"]
    assert {f"/{NAME}/odometry", f"/{NAME}/tf_odometry", f"/{NAME}/controller_state"} <= c.probe.publishers
    # configure_succeeds_tf_*: prefix given / blank / disabled, with and without a namespace
    for params, ns, frames in (({"tf_frame_prefix": "test_prefix"}, "/", ("test_prefix/odom", "test_prefix/base_link")),
                               ({"tf_frame_prefix": ""}, "/", ("odom", "base_link")),
                               ({"tf_frame_prefix_enable": False, "tf_frame_prefix": "test_prefix"}, "/test_ns",
                                ("odom", "base_link")),
                               ({"tf_frame_prefix": ""}, "/test_ns", ("test_ns/odom", "test_ns/base_link"))):
        c, _, _ = running(params, namespace=ns)
        update(c, START_NS, 0.01)
        odom = c.probe.sent(c.probe.resolve("~/odometry"))[-1]
        assert (odom["header"]["frame_id"], odom["child_frame_id"]) == frames


def test_old_references_stop_the_wheels_fresh_ones_drive_them() -> None:
    # when_ref_msg_old_expect_cmnd_itfs_set_to_zero_otherwise_to_valid_cmnds
    c, cmd, _ = running()
    topic = f"/{NAME}/reference"
    c.probe.deliver(topic, stamped(START_NS - round(1.0 * NS)))  # older than 0.9 s
    assert "older by 1.0000000000 than allowed timeout (0.9000)" in c.probe.log.text("ERROR")
    update(c, START_NS, 0.01)
    assert [h.value for h in cmd] == [0.0] * 4 and all(math.isnan(r.value) for r in c.reference_interfaces)
    c.probe.deliver(topic, stamped(START_NS - 10_000_000))
    update(c, START_NS, 0.01)
    assert [h.value for h in cmd] == [3.0] * 4  # 1 / 0.5 · (1.5 − 0 − 1 · 0)
    assert all(math.isnan(r.value) for r in c.reference_interfaces)
    update(c, START_NS + NS, 0.01)  # 1 s later the reference has timed out
    assert [h.value for h in cmd] == [0.0] * 4
    c.on_deactivate(State.ACTIVE)
    assert all(math.isnan(h.value) for h in cmd)


def test_timeout_zero_uses_each_reference_once() -> None:
    # when_reference_timeout_is_zero_expect_reference_msg_being_used_only_once
    c, cmd, _ = running({"reference_timeout": 0.0})
    c.probe.deliver(f"/{NAME}/reference", stamped(0))  # a zero stamp is "now"
    assert "Timestamp in header is missing" in c.probe.log.text("WARN")
    update(c, START_NS, 0.01)
    assert [h.value for h in cmd] == [3.0] * 4
    update(c, START_NS + 10_000_000, 0.01)
    assert [h.value for h in cmd] == [0.0] * 4


def test_chained_references_drive_the_wheels() -> None:
    # when_controller_in_chainable_mode_expect_receiving_commands_from_reference_interfaces_directly
    c, cmd, _ = running(chained=True)
    refs(c, 3.0, 0.0, 0.0)
    update(c, START_NS, 0.01)
    assert [h.value for h in cmd] == [6.0] * 4
    assert all(math.isnan(r.value) for r in c.reference_interfaces)


def test_acceleration_limits_per_direction() -> None:
    # test_speed_limiter_linear_x: 0 → 1 m/s at 2 m/s² (0.5 s), → 0 at −4 (0.25 s), → −1 at −8 (0.125 s),
    # → 0 at 10 (0.1 s); dt 1 ms, wheels 0.5 m
    c, cmd, _ = running(LIMITS, chained=True)
    for _ in range(3):
        refs(c, 0.0, 0.0, 0.0)
        update(c, START_NS, 0.01)
    dt = 0.001
    for target, seconds, towards in ((1.0, 0.5, 1), (0.0, 0.25, -1), (-1.0, 0.125, -1), (0.0, 0.1, 1)):
        for _ in range(math.floor(seconds / dt) - 1):
            refs(c, target, 0.0, 0.0)
            update(c, START_NS, dt)
            assert (target / 0.5 - cmd[0].value) * towards > 0  # not there yet
        refs(c, target, 0.0, 0.0)
        update(c, START_NS, dt)
        assert cmd[0].value == pytest.approx(target / 0.5, abs=1e-3)
        for _ in range(3):
            refs(c, target, 0.0, 0.0)
            update(c, START_NS, 0.01)


def test_odometry_integrates_the_wheels() -> None:
    # SideToSideAndRotationOdometryTest: offset base frame (1, 2, 3 rad), alternating sideways and turning at 50 Hz
    params = {**WHEELS, "reference_timeout": 5.0, "kinematics.base_frame_offset.x": 1.0,
              "kinematics.base_frame_offset.y": 2.0, "kinematics.base_frame_offset.theta": 3.0,
              "kinematics.wheels_radius": 0.05, "kinematics.sum_of_robot_center_projection_on_X_Y_axis": 0.2925}
    c, cmd, state = running(params, chained=True)
    t = START_NS
    for k in range(50):
        refs(c, *[(0.0, 2.0, 0.0), (0.0, 0.0, -0.5), (0.0, -2.0, 0.0), (0.0, 0.0, 0.5)][k % 4])
        update(c, t, 0.02)
        t += 20_000_000
        for s, h in zip(state, cmd, strict=True):
            s.value = h.value
    odom = c.odometry
    assert abs(odom.x_m) < 1.0 and abs(odom.y_m) < 1.0 and abs(odom.heading_rad) < math.pi
    # the inverse and forward kinematics undo each other, offset or not
    for g in (c.geometry, MecanumGeometry(0.5, 1.0)):
        for twist in ((1.5, 0.0, 0.0), (0.0, 0.7, 0.0), (0.3, -0.2, 0.9)):
            assert body_twist(g, *wheel_velocities_radps(g, *twist)) == pytest.approx(twist)
    # test_speed_limiter_linear_y's wheels for a sideways v: (−v, v, −v, v) / r
    assert wheel_velocities_radps(MecanumGeometry(0.5, 1.0), 0.0, 1.0, 0.0) == (-2.0, 2.0, -2.0, 2.0)
