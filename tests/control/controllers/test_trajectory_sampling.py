"""joint_trajectory_controller's trajectory sampling and control_toolbox's PID against the expected values of their
upstream tests (ros2_controllers jazzy: joint_trajectory_controller/test/test_trajectory.cpp; control_toolbox
jazzy: test/pid_tests.cpp)."""

from __future__ import annotations

import math

import pytest

from diffctl.control.math.pid import Pid, PidGains
from diffctl.control.math.trajectory import (
    Trajectory,
    TrajectoryPoint,
    decelerating_stop,
    interpolate,
    shortest_angular_distance,
)

NS = 1_000_000_000
EPS = 1e-8
NOW = 1_700_000_000 * NS  # test_trajectory.cpp samples from rclcpp::Clock().now()


def approx(x: float) -> object:
    return pytest.approx(x, abs=EPS)


def test_positions_only_are_linear_between_waypoints_and_hold_the_last() -> None:
    # TestTrajectory.sample_trajectory_positions: 0 (now) → 1 (1 s) → 2 (2 s) → 3 (3 s)
    points = [TrajectoryPoint([float(k)], time_from_start_ns=k * NS) for k in (1, 2, 3)]
    traj = Trajectory(points, 0)
    traj.set_state_before(NOW, TrajectoryPoint([0.0]), [False])
    s = traj.sample(NOW)
    assert (s.start, s.end) == (0, 0) and traj.last_sample_index == 0
    assert s.point.positions[0] == approx(0.0) and s.point.velocities[0] == approx(1.0)
    assert s.point.accelerations[0] == approx(0.0)
    assert traj.sample(NOW - NS // 2) is None  # before the state it starts from
    s = traj.sample(NOW + NS // 2)
    assert (s.start, s.end) == (0, 0) and s.point.positions[0] == approx(0.5) and s.point.velocities[0] == approx(1.0)
    s = traj.sample(NOW + NS)
    assert (s.start, s.end) == (0, 1) and s.point.positions[0] == approx(1.0)
    assert traj.sample(NOW + 3 * NS // 2).point.positions[0] == approx(1.5)
    s = traj.sample(NOW + 5 * NS // 2)
    assert traj.last_sample_index == 1 and s.point.positions[0] == approx(2.5)
    assert traj.sample(NOW + 3 * NS).point.positions[0] == approx(3.0) and traj.last_sample_index == 2
    for late_ns in (3_125_000_000, 30 * NS):  # past the end: the last waypoint, segment "end"
        s = traj.sample(NOW + late_ns)
        assert (s.start, s.end) == (2, 3) and s.point.positions[0] == approx(3.0)


def test_cubic_and_quintic_segments() -> None:
    # TestTrajectory.interpolation_pos_vel: x³ − 2x from t = 1 s to 3 s
    a = TrajectoryPoint([0.0], [-2.0], [], time_from_start_ns=NS)
    b = TrajectoryPoint([4.0], [10.0], [0.0], time_from_start_ns=3 * NS)
    s = interpolate(NS, a, 3 * NS, b, NS)
    assert (s.positions[0], s.velocities[0], s.accelerations[0]) == (approx(0.0), approx(-2.0), approx(0.0))
    s = interpolate(NS, a, 3 * NS, b, NS + round(math.sqrt(2.0) * NS))
    assert s.positions[0] == pytest.approx(0.0, abs=1e-8) and s.velocities[0] == pytest.approx(4.0, abs=1e-8)
    assert s.accelerations[0] == pytest.approx(6.0 * math.sqrt(2.0), abs=1e-8)
    s = interpolate(NS, a, 3 * NS, b, 3 * NS)
    assert (s.positions[0], s.velocities[0], s.accelerations[0]) == (approx(4.0), approx(10.0), approx(12.0))
    # TestTrajectory.interpolation_pos_vel_accel: x(x−1)(x−2)(x−3)(x−4)
    a = TrajectoryPoint([0.0], [24.0], [-100.0], time_from_start_ns=NS)
    b = TrajectoryPoint([0.0], [4.0], [0.0], time_from_start_ns=3 * NS)
    s = interpolate(NS, a, 3 * NS, b, NS)
    assert (s.positions[0], s.velocities[0], s.accelerations[0]) == (approx(0.0), approx(24.0), approx(-100.0))
    s = interpolate(NS, a, 3 * NS, b, 2 * NS)
    assert (s.positions[0], s.velocities[0], s.accelerations[0]) == (approx(0.0), approx(-6.0), approx(10.0))
    s = interpolate(NS, a, 3 * NS, b, 3 * NS)
    assert (s.positions[0], s.velocities[0], s.accelerations[0]) == (approx(0.0), approx(4.0), approx(0.0))


def test_velocity_only_waypoints_are_integrated() -> None:
    # TestTrajectory.sample_trajectory_velocity_with_interpolation: velocities 1, 2, 1 at 1, 2, 3 s from rest at 0
    points = [TrajectoryPoint([], [v], time_from_start_ns=k * NS) for k, v in ((1, 1.0), (2, 2.0), (3, 1.0))]
    traj = Trajectory(points, 0)
    traj.set_state_before(NOW, TrajectoryPoint([0.0], [0.0]), [False])
    s = traj.sample(NOW)
    assert (s.point.positions[0], s.point.velocities[0], s.point.accelerations[0]) == (approx(0), approx(0), approx(1))
    s = traj.sample(NOW + NS // 2)
    assert s.point.positions[0] == approx(0.0 + (0.0 + (0.5 - 0.0) / 2) * 0.5)
    assert s.point.velocities[0] == approx(0.5) and s.point.accelerations[0] == approx(1.0)
    first = 0.5  # (0 + 1) / 2 · 1 s
    s = traj.sample(NOW + NS)
    assert (s.start, s.end) == (0, 1) and s.point.positions[0] == approx(first)
    assert s.point.velocities[0] == approx(1.0) and s.point.accelerations[0] == approx(2.0 - 1.0 / 1.0)
    s = traj.sample(NOW + 3 * NS // 2)
    assert s.point.positions[0] == approx(first + (1.0 + (1.5 - 1.0) / 2) * 0.5)
    assert s.point.velocities[0] == approx(1.5)
    second = first + 1.5
    s = traj.sample(NOW + 2 * NS)
    assert traj.last_sample_index == 1 and s.point.positions[0] == approx(second)
    assert s.point.accelerations[0] == approx(1.0 - 2.0 / 1.0)
    third = second + 1.5
    s = traj.sample(NOW + 3 * NS)
    assert (s.start, s.end) == (2, 3) and s.point.positions[0] == approx(third) and s.point.velocities[0] == approx(1.0)
    assert s.point.accelerations[0] == approx(0.0)


def test_continuous_joints_start_from_the_nearest_turn() -> None:
    # A continuous joint at 3.0 rad going to -3.0 rad turns 0.28 rad forward, not 6 rad back.
    traj = Trajectory([TrajectoryPoint([-3.0], time_from_start_ns=NS)], 0)
    traj.set_state_before(NOW, TrajectoryPoint([3.0]), [True])
    assert traj.state_before.positions[0] == pytest.approx(-3.0 - (2 * math.pi - 6.0))
    assert shortest_angular_distance(3.0, -3.0) == pytest.approx(2 * math.pi - 6.0)
    assert shortest_angular_distance(-3.0, 3.0) == pytest.approx(6.0 - 2 * math.pi)


def test_braking_to_a_stop_at_the_deceleration_limit() -> None:
    points = decelerating_stop([1.0, 0.0], [2.0, -1.0], [4.0, 4.0], 0.1)
    assert len(points) == 6  # the slower joint needs 0.5 s
    assert points[-1].positions == pytest.approx([1.0 + 4.0 / 8.0, -1.0 / 8.0])
    assert points[1].velocities == pytest.approx([1.6, -0.6]) and points[1].accelerations == pytest.approx([-4.0, 4.0])
    assert points[3].velocities == pytest.approx([0.8, 0.0]) and points[3].positions[1] == pytest.approx(-1.0 / 8.0)
    assert points[5].velocities == [0.0, 0.0]


def run(pid: Pid, steps: list[tuple[float, float]]) -> list[tuple[float, float]]:
    return [(pid.compute_command(e, None, dt), pid.i_term) for e, dt in steps]


def test_pid_terms_and_anti_windup_as_control_toolbox() -> None:
    # CommandTest.completePIDTest (legacy: deprecated constructor p, i, d, i_max, i_min)
    pid = Pid(PidGains(1.0, 1.0, 1.0, i_max=5.0, i_min=-5.0))
    assert [c for c, _ in run(pid, [(-0.5, 1.0), (-0.5, 1.0), (-1.0, 1.0)])] == [-1.5, -1.5, -3.5]
    # CommandTest.integralOnlyTest, reset keeping the integral
    pid = Pid(PidGains(0.0, 1.0, 0.0, i_max=5.0, i_min=-5.0))
    assert [c for c, _ in run(pid, [(-0.5, 1.0), (-0.5, 1.0), (0.0, 1.0), (0.0, 1.0), (1.0, 1.0)])] == \
        [-0.5, -1.0, -1.0, -1.0, 0.0]
    pid.compute_command(-0.5, None, 1.0)
    pid.reset(keep_integral=True)
    assert pid.compute_command(0.0, None, 1.0) == -0.5
    # CommandTest.derivativeOnlyTest
    pid = Pid(PidGains(0.0, 0.0, 1.0))
    assert [c for c, _ in run(pid, [(-0.5, 1.0), (-0.5, 1.0), (-0.5, 0.1), (-1.0, 1.0), (-0.5, 1.0)])] == \
        [-0.5, 0.0, 0.0, -0.5, 0.5]
    # ParameterTest.integrationClampTest and negativeIntegrationAntiwindupTest (legacy_antiwindup)
    pid = Pid(PidGains(0.0, 1.0, 0.0, i_max=1.0, i_min=-1.0))
    assert [c for c, _ in run(pid, [(-10.03, 1.0), (30.0, 1.0)])] == [-1.0, 1.0]
    pid = Pid(PidGains(0.0, -2.5, 0.0, i_max=0.5, i_min=-0.2, legacy_antiwindup=True))
    assert [c for c, _ in run(pid, [(0.1, 1.0), (0.1, 1.0), (-0.05, 1.0), (0.1, 1.0)])] == \
        pytest.approx([-0.2, -0.2, -0.075, -0.2], abs=1e-9)
    # ParameterTest.outputClampTest (back calculation, default time constant)
    pid = Pid(PidGains(1.0, 0.0, 0.0, 1.0, -1.0, "back_calculation"))
    assert [pid.compute_command(e, None, 1.0) for e in (0.5, 1.0, 2.0, 100.0, -0.5, -2.0, -100.0)] == \
        [0.5, 1.0, 1.0, 1.0, -0.5, -1.0, -1.0]
    # CommandTest.backCalculationPIDTest and conditionalIntegrationPIDTest: (command, integral) per step
    pid = Pid(PidGains(0.0, 1.0, 0.0, 5.0, -5.0, "back_calculation", tracking_time_constant=1.0))
    assert run(pid, [(e, 1.0) for e in (1.0, 2.0, 3.0, 1.0, 2.0, -1.0, 1.0)]) == \
        [(0.0, 1.0), (1.0, 3.0), (3.0, 6.0), (5.0, 6.0), (5.0, 7.0), (5.0, 4.0), (4.0, 5.0)]
    pid = Pid(PidGains(0.0, 1.0, 0.0, 5.0, -5.0, "conditional_integration", tracking_time_constant=1.0))
    assert run(pid, [(e, 1.0) for e in (1.0, 2.0, 3.0, 1.0, 2.0, -1.0, 0.0)]) == \
        [(0.0, 1.0), (1.0, 3.0), (3.0, 6.0), (5.0, 6.0), (5.0, 6.0), (5.0, 5.0), (5.0, 5.0)]


def test_pid_gains_control_toolbox_refuses() -> None:
    assert "u_min (1) must be less than u_max (-1)" in PidGains(u_max=-1.0, u_min=1.0).problem()
    assert "i_min to be smaller or equal to 0" in PidGains(i_min=0.5).problem()
    with pytest.raises(ValueError, match="Unknown antiwindup strategy"):
        Pid(PidGains(antiwindup_strategy="clamp"))
    assert math.isnan(Pid(PidGains(1.0)).compute_command(math.nan, 0.0, 0.01))
