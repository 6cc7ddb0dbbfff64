"""steering_controllers_library's kinematics and the ackermann, bicycle and tricycle steering controllers driven
directly (real client nodes), with the values of upstream's test_steering_odometry.cpp and
test_ackermann_steering_controller.cpp (ros2_controllers jazzy): wheelbase 3.24644, traction track 1.76868, wheel
radius 0.45; a reference of 0.1 m/s and 0.2 rad/s → both traction wheels 0.2222 rad/s, both steering joints
1.41798 rad while the measured steering is still 0."""

from __future__ import annotations

import math

import pytest
from controller_harness import NS, START_NS, activate, configure, hand_interfaces, make_controller, update

from diffctl.control.controller_interface import CallbackReturn
from diffctl.control.controllers.ackermann_steering_controller import AckermannSteeringController
from diffctl.control.controllers.bicycle_steering_controller import BicycleSteeringController
from diffctl.control.controllers.tricycle_steering_controller import TricycleSteeringController
from diffctl.control.lifecycle import State
from diffctl.control.math.steering_odometry import ACKERMANN, BICYCLE, TRICYCLE, SteeringKinematics

pytestmark = pytest.mark.usefixtures("client_bus")

COMMON_THRESHOLD = 1e-6


def kinematics(config: int, radius=1.0, base=2.0, track=1.0) -> SteeringKinematics:
    k = SteeringKinematics(1)
    k.set_wheel_params(radius, base, track)
    k.config = config
    return k


def test_forward_kinematics_as_upstream() -> None:
    # ackermann_odometry, tricycle_odometry, bicycle_odometry (radius 1, wheelbase 1, track 1)
    for config, wheels, angles, linear in ((ACKERMANN, (1.0, 1.0), (0.1, 0.1), 1.002),
                                           (TRICYCLE, (1.0, 1.0), (0.1,), 1.002), (BICYCLE, (1.0,), (0.1,), 1.0)):
        k = kinematics(config, 1.0, 1.0, 1.0)
        assert k.update_from_velocity(wheels, angles, 0.1)
        assert k.linear_mps == pytest.approx(linear, abs=1e-3) and k.angular_radps == pytest.approx(0.1, abs=1e-3)
        assert k.pose.x_m == pytest.approx(0.1, abs=1e-3) and k.pose.heading_rad == pytest.approx(0.01, abs=1e-3)
    # ackermann_odometry_openloop_*: 2 m/s for 0.5 s → 1 m; turning left / right
    k = kinematics(ACKERMANN)
    k.update_open_loop(2.0, 0.0, 0.5)
    assert (k.linear_mps, k.pose.x_m, k.pose.y_m) == (2.0, 1.0, 0.0)
    for turn, side in ((1.0, 1), (-1.0, -1)):
        k = kinematics(ACKERMANN)
        k.update_open_loop(1.0, turn, 1.0)
        assert k.pose.x_m > 0 and k.pose.y_m * side > 0


def test_inverse_kinematics_as_upstream() -> None:
    # *_IK_linear: straight, no steering
    for config in (ACKERMANN, TRICYCLE, BICYCLE):
        k = kinematics(config)
        k.update_open_loop(1.0, 0.0, 1.0)
        wheels, angles = k.commands(1.0, 0.0, True)
        assert len(set(wheels)) == 1 and wheels[0] > 0 and set(angles) == {0.0}
    # ackermann_IK_left / _right: the outer wheel faster, the inner steered more
    for turn in (0.1, -0.1):
        k = kinematics(ACKERMANN)
        k.update_from_position((0.0,), (0.2 if turn > 0 else -0.2,), 1.0)  # already turned
        (right, left), (steer_r, steer_l) = k.commands(1.0, turn, False)
        assert right > 0 and (right > left if turn > 0 else right < left)
        assert (steer_r < steer_l and steer_r > 0) if turn > 0 else (abs(steer_r) > abs(steer_l) and steer_r < 0)
    # *_IK_right_steering_limited: the wheels slow down while the steering is far from its target
    for config in (ACKERMANN, TRICYCLE, BICYCLE):
        k = kinematics(config)
        k.update_from_position((0.0,), (-0.1,), 1.0)
        fast = k.commands(1.0, -0.5, False, False)[0]
        slow = k.commands(1.0, -0.5, False, True)[0]
        assert all(0 < s < f for s, f in zip(slow, fast, strict=True))
        k.update_from_position((0.0,), (math.pi,), 1.0)
        slowest = k.commands(1.0, -0.5, False, True)[0]
        assert all(0 < x < s for x, s in zip(slowest, slow, strict=True))
    assert kinematics(BICYCLE).commands(1.0, 0.1, False)[0] == [1.0]


ACKERMANN_PARAMS = {"reference_timeout": 2.0, "open_loop": False, "velocity_rolling_window_size": 10,
                    "position_feedback": False,
                    "traction_joints_names": ["rear_right_wheel_joint", "rear_left_wheel_joint"],
                    "steering_joints_names": ["front_right_steering_joint", "front_left_steering_joint"],
                    "wheelbase": 3.24644, "traction_track_width": 1.76868, "traction_wheels_radius": 0.45}
NAME = "test_ackermann_steering_controller"


def running(cls_, name, params, chained=False):
    c = make_controller(cls_, name, params)
    configure(c)
    cmd, state = hand_interfaces(c)  # upstream's fixture: commands 1.1, 3.3, 2.2, 4.4; states 0.5, 0.5, 0, 0
    for handle, value in zip(cmd.values(), (1.1, 3.3, 2.2, 4.4), strict=False):
        handle.value = value
    for handle, value in zip(state.values(), (0.5, 0.5, 0.0, 0.0), strict=False):
        handle.value = value
    if chained:
        c.set_chained_mode(True)
    activate(c)
    return c, list(cmd.values())


def test_ackermann_controller_update_logic() -> None:
    # check_exported_interfaces, receive_message_and_publish_updated_status, test_update_logic(_chained)
    c, cmd = running(AckermannSteeringController, NAME, ACKERMANN_PARAMS)
    assert c.command_interface_configuration().names == [
        "rear_right_wheel_joint/velocity", "rear_left_wheel_joint/velocity", "front_right_steering_joint/position",
        "front_left_steering_joint/position"]
    assert c.state_interface_configuration().names == [
        "rear_right_wheel_joint/velocity", "rear_left_wheel_joint/velocity", "front_right_steering_joint/position",
        "front_left_steering_joint/position"]
    assert [r.name for r in c.reference_interfaces] == [f"{NAME}/linear/velocity", f"{NAME}/angular/velocity"]
    update(c, START_NS, 0.01)
    status = c.probe.sent(f"/{NAME}/controller_state")[-1]
    assert status["linear_velocity_command"] == [0.0, 0.0] and status["steering_angle_command"] == [2.2, 4.4]
    c.probe.deliver(f"/{NAME}/reference", {"header": {"stamp": {"sec": START_NS // NS}},
                                           "twist": {"linear": {"x": 0.1}, "angular": {"z": 0.2}}})
    update(c, START_NS, 0.01)
    expected = [0.22222222222222224, 0.22222222222222224, 1.4179821977774734, 1.4179821977774734]
    assert [h.value for h in cmd] == pytest.approx(expected, abs=COMMON_THRESHOLD)
    status = c.probe.sent(f"/{NAME}/controller_state")[-1]
    assert status["linear_velocity_command"] + status["steering_angle_command"] == pytest.approx(expected)
    assert status["traction_wheels_velocity"] == [0.5, 0.5] and status["steer_positions"] == [0.0, 0.0]
    assert all(math.isnan(r.value) for r in c.reference_interfaces)
    odom = c.probe.sent(f"/{NAME}/odometry")[-1]
    assert odom["header"]["frame_id"] == "odom" and odom["twist"]["twist"]["linear"]["x"] == pytest.approx(0.225)
    assert c.probe.sent(f"/{NAME}/tf_odometry")
    c.on_deactivate(State.ACTIVE)
    assert all(math.isnan(h.value) for h in cmd)
    c, cmd = running(AckermannSteeringController, NAME, ACKERMANN_PARAMS, chained=True)
    c.reference_interfaces[0].value, c.reference_interfaces[1].value = 0.1, 0.2
    update(c, START_NS, 0.01)
    assert [h.value for h in cmd] == pytest.approx(expected, abs=COMMON_THRESHOLD)


def test_references_time_out_and_bad_ones_are_dropped() -> None:
    c, cmd = running(AckermannSteeringController, NAME, ACKERMANN_PARAMS)
    c.probe.deliver(f"/{NAME}/reference", {"header": {"stamp": {"sec": START_NS // NS - 3}},
                                           "twist": {"linear": {"x": 0.1}}})
    assert "older for 3.0000000000 which is more then allowed timeout (2.0000)" in c.probe.log.text("ERROR")
    c.probe.deliver(f"/{NAME}/reference", {"twist": {"linear": {"x": 0.1}, "angular": {"z": math.inf}}})
    assert "angular.z is inf" in c.probe.log.text("WARN")
    c.probe.deliver(f"/{NAME}/reference", {"twist": {"linear": {"x": 0.1}}})  # zero stamp: now
    update(c, START_NS + NS, 0.01)
    assert cmd[0].value == pytest.approx(0.1 / 0.45)
    update(c, START_NS + 4 * NS, 0.01)  # 4 s later: timed out, the wheels stop
    assert cmd[0].value == 0.0 and cmd[1].value == 0.0


def test_bicycle_and_tricycle_variants_and_deprecated_names() -> None:
    c, cmd = running(BicycleSteeringController, "bicycle", {
        "traction_joints_names": ["rear_wheel_joint"], "steering_joints_names": ["steering_axis_joint"],
        "wheelbase": 2.0, "traction_wheel_radius": 0.5})
    c.probe.deliver("/bicycle/reference", {"twist": {"linear": {"x": 1.0}, "angular": {"z": 0.5}}})
    update(c, START_NS, 0.01)
    assert [h.value for h in cmd] == pytest.approx([2.0, math.atan(1.0)])
    # the deprecated rear/front names with front_steering map onto traction/steering, with warnings
    c, cmd = running(TricycleSteeringController, "tricycle", {
        "rear_wheels_names": ["right_wheel", "left_wheel"], "front_wheels_names": ["steer"], "wheelbase": 1.0,
        "wheel_track": 0.5, "rear_wheels_radius": 0.25})
    log = c.probe.log.text("WARN")
    assert "DEPRECATED parameter 'rear_wheels_names'" in log and "DEPRECATED parameter 'wheel_track'" in log
    assert c.command_interface_configuration().names == ["right_wheel/velocity", "left_wheel/velocity",
                                                         "steer/position"]
    # wrong joint counts and a missing track are refused as upstream
    bad = make_controller(AckermannSteeringController, NAME, {**ACKERMANN_PARAMS,
                                                               "steering_joints_names": ["only_one"]})
    assert bad.on_configure(State.UNCONFIGURED) is CallbackReturn.ERROR
    assert "Ackermann configuration requires exactly two steering joints, but 1 were provided" in \
        bad.probe.log.text("ERROR")
    bad = make_controller(TricycleSteeringController, "tricycle", {
        "traction_joints_names": ["r", "l"], "steering_joints_names": ["s"], "wheelbase": 1.0,
        "traction_wheels_radius": 0.25})
    assert bad.on_configure(State.UNCONFIGURED) is CallbackReturn.ERROR
    assert "parameter 'traction_track_width' is not set" in bad.probe.log.text("FATAL")
