"""tricycle_controller driven directly (a real client node) and its limiters, with the values of upstream's
test_tricycle_controller.cpp and test_traction_limiter.cpp (ros2_controllers jazzy)."""

from __future__ import annotations

import math

import pytest
from controller_harness import NS, START_NS, activate, configure, hand_interfaces, make_controller, update

from diffctl.control.controllers.tricycle_controller import TricycleController
from diffctl.control.lifecycle import State
from diffctl.control.math.tricycle_limiters import SteeringLimiter, TractionLimiter
from diffctl.control.math.tricycle_odometry import wheel_command
from diffctl.errors import ParameterError

pytestmark = pytest.mark.usefixtures("client_bus")

NAME = "test_tricycle_controller"
JOINTS = {"traction_joint_name": "traction_joint", "steering_joint_name": "steering_joint"}
N = math.nan


def test_traction_limiter_as_upstream() -> None:
    # testNoLimits, testVelocityLimits, testVelocityNoLimits, testAccelerationLimits, testDecelerationLimits
    assert TractionLimiter().limit(10.0, 0.0, 0.0, 0.5) == (10.0, 1.0)
    lim = TractionLimiter(0.5, 1.0, 0.5, 1.0, 2.0, 3.0, 0.5, 5.0)
    assert lim.limit_velocity(10.0) == (1.0, 0.1)
    assert lim.limit_velocity(0.1) == pytest.approx((0.5, 0.5 / 0.1))
    assert lim.limit_velocity(0.0) == (0.5, 1.0)  # upstream's oddity: a minimum speed even at rest
    assert lim.limit_velocity(-10.0) == (-1.0, -1.0 / -10.0)
    assert lim.limit(10.0, 0.0, 0.0, 0.5) == (0.5, 0.5 / 10.0)
    assert lim.limit(-10.0, 0.0, 0.0, 0.5) == (-0.5, 0.5 / 10.0)
    lim = TractionLimiter(N, N, 0.5, 1.0, 2.0, 3.0, 0.5, 5.0)
    assert lim.limit_velocity(10.0) == (10.0, 1.0)
    assert lim.limit(-10.0, 0.0, 0.0, 0.5) == (-0.5, 0.5 / 10.0)
    assert TractionLimiter(N, N, N, N, N, N, 0.5, 5.0).limit(10.0, 0.0, 0.0, 0.5) == (2.5, 2.5 / 10.0)
    lim = TractionLimiter(N, N, 0.5, 1.0, 2.0, 3.0, N, N)
    assert lim.limit_acceleration(0.0, 0.0, 0.5) == (0.25, 1.0)
    assert lim.limit_acceleration(9.9, 10.0, 0.5)[0] == 9.0
    assert TractionLimiter(N, N, 0.5, 1.0, 2.0, 3.0, 0.5, 5.0).limit_acceleration(0.0, -10.0, 0.5) == (-8.5, 1.0)
    # testWrongParams
    for bad in ((-0.5, 1.0), (1.0, 0.5)):
        with pytest.raises(ValueError):
            TractionLimiter(*bad)
    with pytest.raises(ValueError, match="Acceleration cannot be negative"):
        SteeringLimiter(N, N, N, N, -1.0)
    # the steering limiter: position mirrored, rate bounded
    steer = SteeringLimiter(N, 1.57, N, 1.0)
    assert steer.position == (-1.57, 1.57)
    assert steer.limit(1.0, 0.0, 0.0, 0.1)[0] == pytest.approx(0.1)
    assert steer.limit(-3.0, -1.55, -1.5, 1.0)[0] == -1.57


def test_inverse_kinematics() -> None:
    assert wheel_command(1.0, 0.0, 0.4, 1.0) == (0.0, 1.0)
    assert wheel_command(0.0, 1.0, 1.2, 0.12) == (math.pi / 2, pytest.approx(10.0))  # on the spot
    angle, wheel = wheel_command(1.0, 1.0, 1.0, 0.5)
    assert angle == pytest.approx(math.pi / 4) and wheel == pytest.approx(1.0 / (0.5 * math.cos(math.pi / 4)))


def running(params):
    c = make_controller(TricycleController, NAME, {**JOINTS, **params})
    configure(c)
    cmd, state = hand_interfaces(c, {"traction_joint/velocity": 0.1, "steering_joint/position": 0.2})
    activate(c)
    return c, cmd, state


def test_drives_stops_and_publishes_as_upstream() -> None:
    # correct_initialization_using_parameters: wheelbase 0.4, radius 1; linear 1, angular 0
    c, cmd, _state = running({"wheelbase": 0.4, "wheel_radius": 1.0, "publish_ackermann_command": True})
    assert c.command_interface_configuration().names == ["traction_joint/velocity", "steering_joint/position"]
    c.probe.deliver(f"/{NAME}/cmd_vel", {"twist": {"linear": {"x": 1.0}}})  # zero stamp: now
    update(c, START_NS, 0.01)
    assert (cmd["steering_joint/position"].value, cmd["traction_joint/velocity"].value) == (0.0, 1.0)
    sent = c.probe.sent(f"/{NAME}/cmd_ackermann")[-1]
    assert (sent["speed"], sent["steering_angle"]) == (1.0, 0.0)
    odom = c.probe.sent(f"/{NAME}/odom")[-1]
    assert odom["header"]["frame_id"] == "odom" and odom["child_frame_id"] == "base_link"
    assert "/tf" not in c.probe.publishers  # enable_odom_tf defaults to false
    update(c, START_NS + NS, 0.01)  # 1 s later: past cmd_vel_timeout (500 ms), a stop
    assert cmd["traction_joint/velocity"].value == 0.0
    c.on_deactivate(State.ACTIVE)
    assert (cmd["steering_joint/position"].value, cmd["traction_joint/velocity"].value) == (0.0, 0.0)


def test_odometry_follows_the_wheel_along_an_arc() -> None:
    c, _cmd, state = running({"wheelbase": 1.0, "wheel_radius": 0.5, "enable_odom_tf": True,
                             "velocity_rolling_window_size": 1})
    state["traction_joint/velocity"].value = 2.0  # rim 1 m/s
    state["steering_joint/position"].value = math.pi / 6
    t = START_NS
    for _ in range(100):
        update(c, t, 0.01)
        t += 10_000_000
    odom = c.odometry
    turn = 0.5 / 1.0  # rim · sin(30°) / wheelbase
    assert odom.angular_radps == pytest.approx(turn) and odom.linear_mps == pytest.approx(math.cos(math.pi / 6))
    radius = math.cos(math.pi / 6) / turn
    assert (odom.pose.x_m, odom.pose.y_m) == pytest.approx((radius * math.sin(0.5), radius * (1 - math.cos(0.5))))
    tf = c.probe.sent("/tf")[-1]["transforms"][0]
    assert tf["transform"]["translation"]["x"] == pytest.approx(odom.pose.x_m)


def test_parameters_and_bad_commands() -> None:
    with pytest.raises(ParameterError) as e:
        make_controller(TricycleController, NAME, {"traction_joint_name": "t", "wheelbase": 1.0, "wheel_radius": 1.0})
    assert e.value.field == f"{NAME}.steering_joint_name"
    c = make_controller(TricycleController, NAME, {**JOINTS, "wheelbase": 1.0, "wheel_radius": 1.0,
                                                  "use_stamped_vel": True})
    assert "'test_tricycle_controller.use_stamped_vel' is ignored" in c.probe.log.text("WARN")
    c = make_controller(TricycleController, NAME, {**JOINTS, "wheelbase": 1.0, "wheel_radius": 1.0,
                                                  "traction.max_velocity": -1.0})
    assert c.on_configure(State.UNCONFIGURED).name == "ERROR"
    c, _cmd, _ = running({"wheelbase": 1.0, "wheel_radius": 1.0})
    c.probe.deliver(f"/{NAME}/cmd_vel", {"twist": {"linear": {"x": math.inf}}})
    assert "linear.x is inf" in c.probe.log.text("WARN")
