"""An idle robot stands still: within 1 mm and 0.001 rad per minute of sim time, on several robot shapes, with
its wheels free (no controller) and held at zero (a drive controller with no command), in real PyBullet."""

from __future__ import annotations

import math

import pytest

from diffctl.description.pose import Pose
from diffctl.description.sdf_loader import load_model, parse_model
from diffctl.description.urdf.to_model import urdf_model
from tests.sim import idle_robots as robots
from tests.sim.sim_helpers import CAR, build, ground, sdf_world

MINUTE_S = 60.0
SETTLE_S = 1.0

SHAPES = {
    "tutorial car (frictionless sphere caster)": lambda: load_model(CAR, name="robot"),
    "turtlebot-like, sphere caster mu 0.1": lambda: parse_model(robots.turtlebot_like("sphere", 0.1)),
    "turtlebot-like, frictionless sphere caster": lambda: parse_model(robots.turtlebot_like("sphere", 0.0)),
    "turtlebot-like, sliding box caster": lambda: parse_model(robots.turtlebot_like("box", 0.1)),
    "4-wheel skid steer": lambda: parse_model(robots.skid_steer()),
    "URDF robot with a caster and <gazebo> friction": lambda: urdf_model(robots.urdf_with_caster()),
}


def _yaw(q: tuple[float, float, float, float]) -> float:
    x, y, z, w = q
    return math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def _idle_drift(model, hold: bool) -> tuple[float, float, float]:
    pw, _ = build(sdf_world(ground()))
    try:
        robot = pw.add_model(model)
        if hold:
            for h in robot.joints.values():
                robot.set_joint_velocity(h, 0.0)
        for _ in range(round(SETTLE_S / pw.step_s)):
            pw.step()
        start = robot.pose()
        for _ in range(round(MINUTE_S / pw.step_s)):
            pw.step()
        end = robot.pose()
        wheel_speed = max(abs(v) for _, v, _ in robot.joint_states(list(robot.joints.values())))
        d_yaw = abs((_yaw(end.quat) - _yaw(start.quat) + math.pi) % (2 * math.pi) - math.pi)
        return math.dist(start.xyz[:2], end.xyz[:2]), d_yaw, wheel_speed
    finally:
        pw.close()


def _check(shape: str, model, heading: str, holds: tuple[bool, ...] = (False, True)) -> None:
    for hold in holds:
        moved_m, turned_rad, wheel_rad_s = _idle_drift(model(), hold)
        case = f"{shape} {heading}, {'wheels held at 0' if hold else 'no controller'}"
        assert moved_m < 1e-3, f"{case}: crept {moved_m * 1000:.3f} mm in a minute"
        assert turned_rad < 1e-3, f"{case}: turned {turned_rad:.5f} rad in a minute"
        assert wheel_rad_s < 1e-3, f"{case}: wheels still turning at {wheel_rad_s:.4f} rad/s"


@pytest.mark.slow
@pytest.mark.parametrize("shape", list(SHAPES))
def test_an_idle_robot_stays_within_a_millimetre_and_a_milliradian_a_minute(shape: str) -> None:
    _check(shape, SHAPES[shape], "spawned at the origin")


OFF_AXIS = Pose.from_xyz_rpy((0.3, -0.2, 0.0), (0.0, 0.0, 0.7))
SHAPES_OFF_AXIS = {
    "tutorial car (frictionless sphere caster)": lambda: load_model(CAR, name="robot", pose=OFF_AXIS),
    "turtlebot-like, sphere caster mu 0.1": lambda: parse_model(robots.turtlebot_like("sphere", 0.1), pose=OFF_AXIS),
    "turtlebot-like, frictionless sphere caster": lambda: parse_model(
        robots.turtlebot_like("sphere", 0.0), pose=OFF_AXIS
    ),
    "turtlebot-like, sliding box caster": lambda: parse_model(robots.turtlebot_like("box", 0.1), pose=OFF_AXIS),
    "4-wheel skid steer": lambda: parse_model(robots.skid_steer(), pose=OFF_AXIS),
    "URDF robot with a caster and <gazebo> friction": lambda: urdf_model(robots.urdf_with_caster(), pose=OFF_AXIS),
}


@pytest.mark.slow
@pytest.mark.parametrize("shape", list(SHAPES_OFF_AXIS))
def test_idle_robots_spawned_off_the_world_axes_stay_put_too(shape: str) -> None:
    # Free wheels beside a frictionless caster leave rolling without any resistance: before wheels met the
    # ground through a contact disc (diffctl/sim/wheel_contact.py) the tutorial car rolled 2.8 m a minute here.
    _check(shape, SHAPES_OFF_AXIS[shape], "at yaw 0.7")


def test_a_held_wheel_stopped_from_speed_is_anchored_where_it_stopped_not_sprung_back() -> None:
    pw, _ = build(sdf_world(ground()))
    try:
        car = pw.add_model(load_model(CAR, name="robot"))
        wheels = list(car.joints.values())
        for h in wheels:
            car.set_joint_velocity(h, 10.0)
        for _ in range(500):
            pw.step()
        for h in wheels:
            car.set_joint_velocity(h, 0.0)
        for _ in range(300):
            pw.step()
        stopped = car.pose().xyz
        angles = [q for q, _, _ in car.joint_states(wheels)]
        assert not car.settling
        for _ in range(3000):
            pw.step()
        assert math.dist(stopped[:2], car.pose().xyz[:2]) < 1e-4
        assert [q for q, _, _ in car.joint_states(wheels)] == pytest.approx(angles, abs=1e-3)
        # A new command releases the hold at once.
        for h in wheels:
            car.set_joint_velocity(h, 5.0)
        for _ in range(200):
            pw.step()
        assert car.pose().xyz[0] > stopped[0] + 0.01
    finally:
        pw.close()


@pytest.mark.slow
@pytest.mark.parametrize("yaw_rad", [-2.3, 1.2, 3.0])
def test_the_tutorial_car_on_free_wheels_stays_put_at_any_heading(yaw_rad: float) -> None:
    pose = Pose.from_xyz_rpy((-0.4, 0.7, 0.0), (0.0, 0.0, yaw_rad))
    _check(
        "tutorial car (frictionless sphere caster)",
        lambda: load_model(CAR, name="robot", pose=pose),
        f"at yaw {yaw_rad}",
        holds=(False,),
    )
