"""Odometry, rolling mean and kinematics on hand-computed cases: straight, arc, full circle, spin, RK2, feedback."""

from __future__ import annotations

import math

import pytest

from diffctl.control.math.kinematics import heading_quaternion, wheel_velocities_radps
from diffctl.control.math.odometry import Odometry
from diffctl.control.math.rolling_mean import RollingMean

SEP, R = 0.3, 0.04


def odom(window: int = 10) -> Odometry:
    o = Odometry(SEP, R, R, window)
    o.init(0.0)
    return o


def test_straight_from_wheel_positions():
    o = odom()
    assert o.update_from_position(10.0, 10.0, 1.0)  # 10 rad · 0.04 m = 0.4 m
    assert (o.x_m, o.y_m, o.heading_rad) == pytest.approx((0.4, 0.0, 0.0))
    assert o.linear_mps == pytest.approx(0.4)
    assert o.angular_radps == pytest.approx(0.0)


def test_arc_open_loop_is_exact_whatever_the_step():
    # v = 0.2 m/s, ω = 0.5 rad/s for 1 s: radius 0.4 m, heading 0.5 rad
    expected = (0.4 * math.sin(0.5), 0.4 * (1 - math.cos(0.5)), 0.5)
    for steps in (1, 7, 100):
        o = odom()
        for k in range(1, steps + 1):
            o.update_open_loop(0.2, 0.5, k / steps)
        assert (o.x_m, o.y_m, o.heading_rad) == pytest.approx(expected, abs=1e-12)
    assert expected == pytest.approx((0.191770, 0.048967, 0.5), abs=1e-6)


def test_full_circle_returns_to_start():
    o = odom()
    for k in range(1, 1001):  # 10 s at ω = 2π/10 rad/s
        o.update_open_loop(0.2, 2 * math.pi / 10, k * 0.01)
    assert (o.x_m, o.y_m) == pytest.approx((0.0, 0.0), abs=1e-9)
    assert o.heading_rad == pytest.approx(2 * math.pi)


def test_arc_from_wheel_positions_matches_the_open_loop_arc():
    # right wheel 0.35 m/s, left 0.05 m/s → v = 0.2, ω = 1.0 rad/s; after 1 s radius 0.2 m, heading 1 rad
    o = odom()
    for k in range(1, 21):
        t = k * 0.05
        o.update_from_position(0.05 * t / R, 0.35 * t / R, t)
    assert (o.x_m, o.y_m, o.heading_rad) == pytest.approx((0.2 * math.sin(1.0), 0.2 * (1 - math.cos(1.0)), 1.0))
    assert (o.linear_mps, o.angular_radps) == pytest.approx((0.2, 1.0))


def test_spin_in_place_does_not_translate():
    o = odom()
    o.update_from_position(-5.0, 5.0, 1.0)  # ±0.2 m → Δθ = 0.4 / 0.3
    assert (o.x_m, o.y_m) == pytest.approx((0.0, 0.0), abs=1e-12)
    assert o.heading_rad == pytest.approx(0.4 / 0.3)


def test_runge_kutta_fallback_for_tiny_rotation():
    o = odom()
    o.integrate_exact(1.0, 1e-7)
    assert o.x_m == pytest.approx(math.cos(0.5e-7))
    assert o.y_m == pytest.approx(math.sin(0.5e-7))
    assert o.heading_rad == pytest.approx(1e-7)


def test_velocity_feedback_steps_and_rolling_mean_twist():
    o = odom(window=2)
    for k, v in enumerate((1.0, 2.0, 3.0), start=1):
        assert o.update_from_step(v * 0.1, v * 0.1, k * 0.1)
    assert o.x_m == pytest.approx(0.6)
    assert o.linear_mps == pytest.approx(2.5)  # mean of the last two: (2 + 3) / 2


def test_updates_closer_than_a_tenth_of_a_millisecond_are_skipped():
    o = odom()
    assert not o.update_from_position(1.0, 1.0, 0.00005)
    assert o.x_m == 0.0
    assert o.update_from_position(1.0, 1.0, 0.1)
    assert o.x_m == pytest.approx(0.04)


def test_init_starts_from_current_wheel_angles_and_time():
    o = Odometry(SEP, R, R)
    o.init(5.0, 3.0, 3.0)  # wheels already turned 3 rad when the controller starts
    o.update_from_position(3.0, 3.0, 5.1)
    assert o.x_m == 0.0
    o.update_from_position(4.0, 4.0, 5.2)
    assert o.x_m == pytest.approx(0.04)
    assert o.linear_mps == pytest.approx(0.2)  # mean of 0 and 0.4 m/s


def test_reset_pose_keeps_the_wheel_reference():
    o = odom()
    o.update_from_position(10.0, 10.0, 1.0)
    o.reset_pose()
    assert (o.x_m, o.y_m, o.heading_rad) == (0.0, 0.0, 0.0)
    o.update_from_position(11.0, 11.0, 2.0)
    assert o.x_m == pytest.approx(0.04)


def test_multipliers_enter_through_the_effective_geometry():
    o = Odometry(SEP * 2.0, R * 0.5, R, 10)
    o.init(0.0)
    o.update_from_position(10.0, 10.0, 1.0)  # left rolls 0.2 m, right 0.4 m
    assert o.heading_rad == pytest.approx(0.2 / 0.6)


def test_rolling_mean_before_and_after_the_window_fills():
    m = RollingMean(3)
    assert m.mean == 0.0
    m.accumulate(3.0)
    assert m.mean == 3.0
    m.accumulate(6.0)
    assert m.mean == 4.5
    for v in (9.0, 12.0):
        m.accumulate(v)
    assert m.mean == 9.0
    with pytest.raises(ValueError):
        RollingMean(0)


def test_wheel_velocities_from_twist():
    assert wheel_velocities_radps(0.2, 0.0, SEP, R, R) == pytest.approx((5.0, 5.0))
    assert wheel_velocities_radps(0.2, 1.0, SEP, R, R) == pytest.approx((1.25, 8.75))
    assert wheel_velocities_radps(0.0, 1.0, SEP, R, R) == pytest.approx((-3.75, 3.75))


def test_heading_quaternion():
    assert heading_quaternion(0.0) == (0.0, 0.0, 0.0, 1.0)
    _, _, z, w = heading_quaternion(math.pi)
    assert (z, w) == pytest.approx((1.0, 0.0))
