"""joint_limits' limiters and the limits read from a robot description, against the values ros2_control's own tests
expect (joint_limits/test/test_joint_range_limiter.cpp, test_joint_soft_limiter.cpp and hardware_interface's
test_component_parser.cpp, Jazzy): each case is (measured position or None, command, expected, clamped?), run in
upstream's order on one limiter, whose previous command carries over from case to case."""

from __future__ import annotations

import math

import pytest

from diffctl.control.joint_limits import (
    JointControlInterfacesData,
    JointLimits,
    JointSaturationLimiter,
    JointSoftLimiter,
    SoftJointLimits,
)
from diffctl.control.joint_limits.joint_limits_helpers import POSITION_BOUNDS_TOLERANCE, JointPositionOutOfBounds
from diffctl.control.joint_limits.joint_limits_urdf import hardware_joint_limits
from diffctl.control.robot_hardware import hardware_infos
from diffctl.errors import DescriptionError

DT_S = 1.0
OUT = 5.0 + 2 * POSITION_BOUNDS_TOLERANCE  # past the ±5 position limits by more than the tolerance
EDGE = POSITION_BOUNDS_TOLERANCE / 2  # past them, within the tolerance
DEG_S = math.pi / 180


def limits(**kw: float) -> JointLimits:
    """JointLimits with each given limit switched on (position=(lo, hi), velocity=…, acceleration=…)."""
    lim = JointLimits()
    for key, value in kw.items():
        if key == "position":
            lim.has_position_limits, (lim.min_position, lim.max_position) = True, value
        else:
            setattr(lim, f"has_{key}_limits", True)
            setattr(lim, f"max_{key}", value)
    return lim


def configured(limiter: JointSaturationLimiter) -> JointSaturationLimiter:
    """After configure() with the all-zero state upstream's harness passes."""
    limiter.configure(JointControlInterfacesData("j", 0.0, 0.0, 0.0, 0.0))
    return limiter


def check(limiter: JointSaturationLimiter, kind: str, cases: list[tuple], **measured: float | None) -> None:
    """Each case: (measured position, command on `kind`, expected, clamped) with fresh actual/desired data."""
    for i, (position, command, expected, clamped) in enumerate(cases):
        actual = JointControlInterfacesData("j", position=position, **measured)
        desired = JointControlInterfacesData("j", **{kind: command})
        assert limiter.enforce(actual, desired, DT_S) is clamped, (i, position, command)
        assert getattr(desired, kind) == pytest.approx(expected, abs=1e-6), (i, position, command)


VELOCITY_NEAR_POSITION_LIMITS = [
    # no position measured: ±max_velocity
    (None, 2.0, 1.0, True), (None, 1.1, 1.0, True), (None, -5.0, -1.0, True), (None, -math.inf, -1.0, True),
    (None, math.inf, 1.0, True), (None, -3.212, -1.0, True), (None, -0.8, -0.8, False), (None, 0.8, 0.8, False),
    (None, 0.12, 0.12, False), (None, 0.0, 0.0, False),
    # no faster than reaches the ±5 position limits within the period; zero past them
    (4.5, 5.0, 0.5, True), (4.8, 5.0, 0.2, True), (4.5, 0.3, 0.3, False), (4.5, 0.5, 0.5, False),
    (5.0, 0.9, 0.0, True), (OUT, 2.0, 0.0, True), (OUT, -2.0, 0.0, True), (4.0, 0.5, 0.5, False),
    (-4.8, -6.0, -0.2, True), (4.3, 5.0, 0.7, True), (-4.5, -5.0, -0.5, True), (-4.5, -0.2, -0.2, False),
    (-3.0, -5.0, -1.0, True), (-3.0, -1.0, -1.0, False), (-5.0, -3.0, 0.0, True), (-5.0, -1.0, 0.0, True),
    (-OUT, -1.0, 0.0, True), (-OUT, -2.0, 0.0, True), (-OUT, 1.0, 0.0, True),
]
# Only with the acceleration limit 0.5: each command within 0.5 of the previous one (order matters).
VELOCITY_BY_ACCELERATION = [
    (0.0, 0.0, False), (1.0, 0.5, True), (1.0, 1.0, False), (-0.2, 0.5, True), (-0.2, 0.0, True),
    (-0.2, -0.2, False), (-0.3, -0.3, False), (-0.9, -0.8, True), (-0.9, -0.9, False), (-2.0, -1.0, True),
    (2.0, -0.5, True), (2.0, 0.0, True), (2.0, 0.5, True), (2.0, 1.0, True), (0.0, 0.5, True), (0.0, 0.0, False),
]


def test_position_commands_saturate_to_position_limits_and_one_periods_travel() -> None:
    lim = limits(position=(-math.pi, math.pi))
    check(configured(JointSaturationLimiter("j", lim)), "position",
          [(None, 4.0, math.pi, True), (None, -5.0, -math.pi, True), (None, 0.0, 0.0, False)])
    lim = limits(position=(-math.pi, math.pi), velocity=1.0)
    # at 1 rad/s a period of 1 s reaches 1 rad from the previous command (seeded from the first command)
    check(JointSaturationLimiter("j", lim), "position", [(None, 0.0, 0.0, False), (None, 2.0, 1.0, True),
                                                          (None, -3.0, 0.0, True)])
    # with no previous command, from the measured position
    check(JointSaturationLimiter("j", lim), "position", [(2.0, -math.pi, 1.0, True)])
    check(JointSaturationLimiter("j", JointLimits()), "position", [(2.0, 5 * math.pi, 5 * math.pi, False)])


def test_velocity_commands_saturate_near_and_past_position_limits_and_by_acceleration() -> None:
    lim = limits(position=(-5.0, 5.0), velocity=1.0)
    limiter = configured(JointSaturationLimiter("j", lim))
    check(limiter, "velocity", VELOCITY_NEAR_POSITION_LIMITS)
    # within the tolerance past a limit: only back inside
    check(limiter, "velocity", [(-5 - EDGE, -3.0, 0.0, True), (-5 - EDGE, 1.0, 1.0, False),
                                (-5 - EDGE, 0.2, 0.2, False), (-5 - EDGE, 2.0, 1.0, True),
                                (5 + EDGE, 3.0, 0.0, True), (5 + EDGE, -1.0, -1.0, False),
                                (5 + EDGE, -0.2, -0.2, False), (5 + EDGE, -2.0, -1.0, True)])
    lim.has_position_limits = False
    lim.has_acceleration_limits, lim.max_acceleration = True, 0.5
    limiter = JointSaturationLimiter("j", lim)
    for position in (None, 10.0, -10.0):
        check(limiter, "velocity", [(position, *case) for case in VELOCITY_BY_ACCELERATION])
    lim.has_position_limits = True
    check(JointSaturationLimiter("j", lim), "velocity", [
        (4.5, 0.0, 0.0, False), (4.5, 1.0, 0.5, True), (4.8, 1.0, 0.2, True), (4.8, -1.0, -0.3, True),
        (4.8, -1.0, -0.8, True), (4.8, -1.0, -1.0, False), (-4.8, -2.0, -0.5, True), (-4.8, -1.0, -0.2, True),
        (-4.3, -1.0, -0.7, True), (-4.3, 0.0, -0.2, True), (-4.3, 0.0, 0.0, False), (-OUT, 1.0, 0.0, True),
        (-OUT, -1.0, 0.0, True), (OUT, 1.0, 0.0, True), (OUT, -1.0, 0.0, True)])
    # velocity limits off: anything passes, wherever the joint is
    lim = limits(position=(-5.0, 5.0), acceleration=0.5)
    check(configured(JointSaturationLimiter("j", lim)), "velocity",
          [(p, v, v, False) for p in (0.0, 5.0, 6.0, -5.0, -6.0) for v in (1000.0, -1000.0)])


def test_effort_commands_saturate_and_push_no_further_out() -> None:
    lim = limits(position=(-5.0, 5.0), velocity=1.0, effort=200.0)
    limiter = configured(JointSaturationLimiter("j", lim))
    for position in (None, 4.0, -4.0):
        for velocity in (None, 0.4, -0.2):
            check(limiter, "effort", [(position, e, max(-200.0, min(200.0, e)), abs(e) > 200)
                                      for e in (20.0, 200.0, 201.0, 0.0, -20.0, -200.0, -201.0)], velocity=velocity)
    # (position, velocity, effort, expected): at a limit (and not moving back in) no effort pushes further out
    for position, velocity, effort, expected in [
        (5.0, 0.0, 20.0, 0.0), (5.0, 0.0, 400.0, 0.0), (6.0, 0.0, 400.0, 0.0), (5.0, 0.0, -20.0, -20.0),
        (5.0, 0.0, -400.0, -200.0), (5.0, -0.2, 400.0, 200.0), (5.0, -0.2, 30.0, 30.0), (5.0, 0.2, 30.0, 0.0),
        (5.0, 0.2, -30.0, -30.0), (-5.0, 0.2, 400.0, 200.0), (-5.0, -0.2, -400.0, 0.0), (-5.0, -0.2, -30.0, 0.0),
        (-5.0, -0.2, 30.0, 30.0), (0.0, 1.5, 30.0, 0.0), (0.0, -1.5, -30.0, 0.0),
    ]:
        check(limiter, "effort", [(position, effort, expected, effort != expected)], velocity=velocity)
    lim.has_effort_limits = False
    check(configured(JointSaturationLimiter("j", lim)), "effort",
          [(5.0, 1e4, 1e4, False), (6.0, -1e4, -1e4, False)], velocity=0.2)


def test_acceleration_deceleration_and_jerk_commands() -> None:
    limiter = configured(JointSaturationLimiter("j", limits(acceleration=0.5)))
    for velocity in (None, 0.4, -0.2):
        check(limiter, "acceleration", [(None, a, max(-0.5, min(0.5, a)), abs(a) > 0.5)
                                        for a in (0.0, 0.5, 0.6, 1.5, -0.5, -0.6, -1.5)], velocity=velocity)
    limiter = JointSaturationLimiter("j", limits(acceleration=0.5, deceleration=0.25))
    check(limiter, "acceleration", [(None, 0.6, 0.5, True), (None, -1.5, -0.5, True)])  # nothing measured
    check(limiter, "acceleration", [(None, 0.2, 0.2, False), (None, 0.8, 0.5, True)], velocity=0.4)
    # slowing down: the deceleration limit
    check(limiter, "acceleration", [(None, -0.25, -0.25, False), (None, -0.6, -0.25, True),
                                    (None, -4.0, -0.25, True)], velocity=0.4)
    check(limiter, "acceleration", [(None, 0.6, 0.25, True), (None, 3.0, 0.25, True)], velocity=-0.4)
    check(JointSaturationLimiter("j", limits(jerk=0.5)), "jerk",
          [(None, j, max(-0.5, min(0.5, j)), abs(j) > 0.5) for j in (0.0, 0.5, 0.6, 1.5, -0.5, -0.6, -1.5)])


def test_all_commands_of_a_joint_together() -> None:
    lim = limits(position=(-5.0, 5.0), velocity=1.0, acceleration=0.5, deceleration=0.25, jerk=2.0)
    # (measured position, measured velocity, desired p, v, a, j, expected p, v, a, j, clamped)
    no_state = [
        (None, None, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, False),
        (None, None, 6.0, 2.0, 1.0, 0.5, 0.5, 0.5, 0.5, 0.5, True),
        (None, None, 6.0, 2.0, 1.0, 0.5, 1.0, 1.0, 0.5, 0.5, True),
        (None, None, 6.0, 2.0, 1.0, 0.5, 1.5, 1.0, 0.5, 0.5, True),
        (None, None, 6.0, 2.0, 1.0, 0.5, 2.0, 1.0, 0.5, 0.5, True),
        (None, None, 3.0, 2.0, 1.0, 0.5, 2.5, 1.0, 0.5, 0.5, True),
        (None, None, 3.0, 2.0, 1.0, 0.5, 3.0, 1.0, 0.5, 0.5, True),
        (None, None, 3.0, 1.0, 0.5, 0.5, 3.0, 1.0, 0.5, 0.5, False),
    ]
    measured = [
        (0.5, 0.0, 6.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, True),
        (1.0, 0.0, 6.0, 0.0, 0.0, 0.0, 1.5, 0.0, 0.0, 0.0, True),
        (1.0, 0.0, 6.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, True),
        (1.0, 0.0, -6.0, 0.0, 0.0, 0.0, 1.5, 0.0, 0.0, 0.0, True),
        (2.0, 0.0, 6.0, 2.0, 1.0, 0.5, 2.0, 0.5, 0.5, 0.5, True),
        (2.0, 0.5, 6.0, 2.0, 1.0, 0.5, 3.0, 1.0, 0.5, 0.5, True),
        (3.0, 0.5, 6.0, 2.0, 1.0, 0.5, 4.0, 1.0, 0.5, 0.5, True),
        (4.0, 0.5, 6.0, 2.0, 1.0, 0.5, 5.0, 1.0, 0.5, 0.5, True),
        (4.8, 0.5, 6.0, 2.0, 1.0, 0.5, 5.0, 0.5, 0.5, 0.5, True),
        (5.0, 0.5, 6.0, 2.0, 1.0, 0.5, 5.0, 0.0, 0.5, 0.5, True),
    ]
    for cases, limiter in ((no_state, configured(JointSaturationLimiter("j", lim))),
                           (measured, JointSaturationLimiter("j", lim))):
        for pos, vel, *rest in cases:
            want, expected, clamped = rest[:4], rest[4:8], rest[8]
            desired = JointControlInterfacesData("j", position=want[0], velocity=want[1], acceleration=want[2],
                                                 jerk=want[3])
            actual = JointControlInterfacesData("j", position=pos, velocity=vel)
            assert limiter.enforce(actual, desired, DT_S) is clamped, (pos, vel, want)
            got = [desired.position, desired.velocity, desired.acceleration, desired.jerk]
            assert got == pytest.approx(expected, abs=1e-6), (pos, vel, want)


def test_nan_commands_and_bad_periods_pass_and_a_far_out_joint_refuses_position_commands() -> None:
    lim = limits(position=(-math.pi, math.pi), velocity=1.0, acceleration=0.5, effort=200.0, jerk=2.0)
    limiter = configured(JointSaturationLimiter("j", lim))
    for kind in ("position", "velocity", "effort", "acceleration", "jerk"):
        desired = JointControlInterfacesData("j", **{kind: math.nan})
        assert not limiter.enforce(JointControlInterfacesData("j"), desired, DT_S)
        assert math.isnan(getattr(desired, kind))
    desired = JointControlInterfacesData("j", velocity=9.0)
    assert not limiter.enforce(JointControlInterfacesData("j"), desired, 0.0) and desired.velocity == 9.0
    # a NaN in between does not become the previous command
    limiter = JointSaturationLimiter("j", lim)
    state = JointControlInterfacesData("j", position=0.0, velocity=0.0)
    for command, clamped in ((0.0, False), (math.nan, False), (2 * math.pi, True)):
        desired = JointControlInterfacesData("j", position=command)
        assert limiter.enforce(state, desired, DT_S) is clamped
    assert desired.position == pytest.approx(0.5)  # from 0 at rest: (0 + 0.5 rad/s² × 1 s) × 1 s
    # a position command while the joint is measured past its limit by more than 0.0087 is a fault
    far = JointControlInterfacesData("j", position=math.pi + 0.01)
    with pytest.raises(JointPositionOutOfBounds, match="Joint position is out of bounds for the joint : 'j'"):
        JointSaturationLimiter("j", lim).enforce(far, JointControlInterfacesData("j", position=0.0), DT_S)
    # after a switch (reset_internals) the previous command is the measurement again
    limiter = JointSaturationLimiter("j", limits(velocity=1.0, acceleration=0.5))
    check(limiter, "velocity", [(None, 0.0, 0.0, False), (None, 1.0, 0.5, True)])
    limiter.reset_internals()
    check(limiter, "velocity", [(None, 1.0, 1.0, False)], velocity=1.0)


def test_soft_limits_slow_the_joint_towards_them() -> None:
    hard = limits(position=(-math.pi, math.pi), velocity=1.0)
    # soft range tighter than one period's reach: clamped to it; from 0.75 a period reaches -0.25
    soft = JointSoftLimiter("j", hard, SoftJointLimits(-0.75, 0.75))
    check(soft, "position", [(None, 2.0, 0.75, True), (None, -3.0, -0.25, True)])
    soft = JointSoftLimiter("j", hard, SoftJointLimits(-1.5, 1.5))
    check(soft, "position", [(0.0, 2.0, 1.0, True)])
    # no position measured: each period covers k_position of the way to the soft bound
    soft = JointSoftLimiter("j", hard, SoftJointLimits(-1.5, 1.5, k_position=0.5))
    check(soft, "position", [(None, 0.2, 0.2, False)])
    previous = 0.2
    while previous < 1.5 - 1e-6:
        expected = previous + (1.5 - previous) * 0.5
        check(soft, "position", [(None, 2.0, expected, True)])
        previous = expected
    # velocity: k_position × the distance to the soft bound, 1°/s back from outside the soft range
    hard = limits(position=(-5.0, 5.0), velocity=1.0)
    soft = JointSoftLimiter("j", hard, SoftJointLimits(-2.0, 4.0, k_position=1.0))
    check(soft, "velocity", [
        (None, 2.0, 1.0, True), (None, -0.8, -0.8, False), (3.0, 5.0, 1.0, True), (3.8, 5.0, 0.2, True),
        (3.5, 0.3, 0.3, False), (4.0, 0.5, 0.0, True), (-2.0, -0.5, 0.0, True), (4.0, -3.0, -1.0, True),
        (4.8, 0.6, -DEG_S, True), (4.3, -5.0, -DEG_S, True), (-4.5, -0.2, DEG_S, True), (-3.0, 5.0, DEG_S, True),
        (OUT, 2.0, 0.0, True), (-OUT, -2.0, 0.0, True), (-5.0, -3.0, DEG_S, True), (5.0, 1.0, -DEG_S, True)])
    # effort: k_velocity × (the soft speed bound − the measured velocity), within ±max_effort
    hard = limits(position=(-5.0, 5.0), velocity=1.0, effort=200.0)
    soft = JointSoftLimiter("j", hard, SoftJointLimits(-4.0, 4.0, k_position=1.0, k_velocity=300.0))
    for position, velocity, effort, expected in [(0.0, 0.5, 200.0, 150.0), (0.0, -0.5, -201.0, -150.0),
                                                 (3.5, 0.4, 200.0, 30.0), (3.5, 0.5, 200.0, 0.0),
                                                 (3.5, 0.4, -20.0, -20.0), (-3.5, -0.4, -200.0, -30.0)]:
        check(soft, "effort", [(position, effort, expected, effort != expected)], velocity=velocity)
    # without soft position limits it is the saturation limiter
    check(JointSoftLimiter("j", hard, SoftJointLimits(k_position=1.0)), "velocity", VELOCITY_NEAR_POSITION_LIMITS)


URDF = """<robot name="r"><link name="base"/>{links}
<joint name="joint1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
  <limit effort="0.1" lower="-3.14159265359" upper="3.14159265359" velocity="0.2"/></joint>
<joint name="joint2" type="revolute"><parent link="base"/><child link="l2"/><axis xyz="0 0 1"/>
  <limit effort="0.1" lower="-3.14159265359" upper="3.14159265359" velocity="0.2"/>
  <safety_controller soft_lower_limit="-1.5" soft_upper_limit="0.5" k_position="10.0" k_velocity="20.0"/></joint>
<joint name="joint3" type="revolute"><parent link="base"/><child link="l3"/><axis xyz="0 0 1"/>
  <limit effort="0.1" lower="-3.14159265359" upper="3.14159265359" velocity="0.2"/></joint>
<joint name="wheel" type="continuous"><parent link="base"/><child link="l4"/><axis xyz="0 1 0"/>
  <limit effort="0.1" velocity="0.2"/></joint>
<ros2_control name="RRBot" type="system"><hardware><plugin>mock_components/GenericSystem</plugin></hardware>{joints}
</ros2_control></robot>"""
LINKS = "".join(f'<link name="l{i}"/>' for i in range(1, 5))


def _limits_of(joints: str, description: str | None = None) -> tuple[dict, list]:
    text = URDF.format(links=LINKS, joints=joints)
    specs, notes = hardware_joint_limits(hardware_infos(text), text if description is None else description)
    return {s.joint: s for s in specs}, notes


def test_limits_are_the_urdfs_narrowed_by_the_interfaces() -> None:
    def iface(name: str, lo: float | None = None, hi: float | None = None, extra: str = "") -> str:
        params = "".join(f'<param name="{k}">{v}</param>' for k, v in (("min", lo), ("max", hi)) if v is not None)
        return f'<command_interface name="{name}">{extra}{params}</command_interface>'

    off = '<limits enable="false"/>'
    joints = (
        '<joint name="joint1">' + iface("position", -1, 1, off) + iface("velocity", -0.05, 0.1)
        + iface("effort", -0.2, 0.2) + iface("acceleration", -0.5, 0.5) + iface("jerk", None, 5.0)
        + '<state_interface name="position"/></joint>'
        '<joint name="joint2"><limits enable="FALSE"/>' + iface("position", -1, 1) + iface("velocity") + "</joint>"
        '<joint name="joint3">' + iface("acceleration", None, 1.0) + "</joint>"
        '<joint name="wheel">' + iface("velocity", -1.0, 1.0) + iface("torque", -1, 1) + "</joint>"
    )
    by_joint, notes = _limits_of(joints)
    j1 = by_joint["joint1"].limits
    assert not j1.has_position_limits and (j1.min_position, j1.max_position) == (-1.7976931348623157e308,
                                                                                 1.7976931348623157e308)
    assert (j1.has_velocity_limits, j1.has_effort_limits, j1.has_acceleration_limits, j1.has_deceleration_limits,
            j1.has_jerk_limits) == (True,) * 5
    assert (j1.max_velocity, j1.max_effort, j1.max_acceleration, j1.max_deceleration, j1.max_jerk) == pytest.approx(
        (0.05, 0.1, 0.5, 0.5, 5.0))
    assert "joint2" not in by_joint  # its limits are disabled: no limiter
    assert ("info", "Joint limits are disabled for joint 'joint2' in hardware 'RRBot'") in notes
    j3 = by_joint["joint3"].limits
    assert (j3.has_position_limits, j3.min_position, j3.max_position) == (True, -3.14159265359, 3.14159265359)
    assert (j3.has_acceleration_limits, j3.has_deceleration_limits, j3.has_jerk_limits) == (True, False, False)
    assert (j3.max_velocity, j3.max_effort, j3.max_acceleration, j3.max_deceleration) == pytest.approx(
        (0.2, 0.1, 1.0, 1.0))
    wheel = by_joint["wheel"].limits
    assert not wheel.has_position_limits and wheel.angle_wraparound and wheel.max_velocity == pytest.approx(0.2)
    assert by_joint["wheel"].soft_limits is None and by_joint["joint1"].soft_limits is None
    assert any(level == "warn" and "Unable to parse the limits for the interface: torque" in text
               for level, text in notes)
    # the safety controller's soft range, within the hard one
    by_joint, _ = _limits_of('<joint name="joint2">' + iface("position") + "</joint>")
    soft = by_joint["joint2"].soft_limits
    assert (soft.min_position, soft.max_position, soft.k_position, soft.k_velocity) == (-1.5, 0.5, 10.0, 20.0)
    # no <limit>: only the interfaces' limits
    text = URDF.format(links=LINKS, joints='<joint name="wheel">' + iface("velocity", None, 0.05) + "</joint>")
    text = text.replace('<limit effort="0.1" velocity="0.2"/>', "")
    specs, _ = hardware_joint_limits(hardware_infos(text), text)
    assert specs[0].limits.has_velocity_limits and specs[0].limits.max_velocity == pytest.approx(0.05)
    assert not specs[0].limits.has_effort_limits


def test_sdf_descriptions_and_bad_input() -> None:
    sdf = """<sdf version="1.11"><model name="m"><link name="a"/><link name="b"/><link name="c"/>
      <joint name="arm" type="revolute"><parent>a</parent><child>b</child><axis><xyz>0 0 1</xyz>
        <limit><lower>-1</lower><upper>1</upper><velocity>0.5</velocity></limit></axis></joint>
      <joint name="wheel" type="continuous"><parent>a</parent><child>c</child><axis><xyz>0 1 0</xyz></axis></joint>
      <ros2_control name="S" type="system"><hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="arm"><command_interface name="position"/></joint>
        <joint name="wheel"><command_interface name="velocity"><param name="max">2</param></command_interface>
        </joint></ros2_control></model></sdf>"""
    specs, _ = hardware_joint_limits(hardware_infos(sdf), sdf)
    arm, wheel = specs[0].limits, specs[1].limits
    assert (arm.min_position, arm.max_position, arm.max_velocity, arm.max_effort) == (-1.0, 1.0, 0.5, math.inf)
    assert wheel.max_velocity == 2.0 and not wheel.has_effort_limits
    with pytest.raises(DescriptionError, match="Joint 'elbow' not found in URDF"):
        hardware_joint_limits(hardware_infos(sdf.replace('"arm"><command', '"elbow"><command')), sdf)
    with pytest.raises(DescriptionError, match="no attribute 'enable' in 'limits' tag"):
        hardware_infos(sdf.replace('<command_interface name="position"/>',
                                   '<command_interface name="position"><limits/></command_interface>'))
    with pytest.raises(DescriptionError, match="'maybe' is not a valid boolean value"):
        hardware_infos(sdf.replace('<command_interface name="position"/>',
                                   '<command_interface name="position"/><limits enable="maybe"/>'))
