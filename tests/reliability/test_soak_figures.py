"""The soak's pure figures: motion in the robot's frame, the odometry/ground-truth window error, memory growth."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from bench.soak import LOOP_NS, SEC, STOP_NS, drive_command
from bench.soak_figures import growth_percent, interpolate, motion_error, relative_motion

coord = st.floats(-100, 100)
angle = st.floats(-math.pi, math.pi)


def test_relative_motion_is_in_the_start_pose_frame() -> None:
    # Facing +y, moving 1 m along +y is 1 m forward; along -x is 1 m to the left.
    assert relative_motion((0, 0, math.pi / 2), (0, 1, math.pi / 2)) == pytest.approx((1, 0, 0), abs=1e-12)
    assert relative_motion((0, 0, math.pi / 2), (-1, 0, math.pi)) == pytest.approx((0, 1, math.pi / 2), abs=1e-12)
    # Turning across ±π is the short way round.
    assert relative_motion((0, 0, 3.1), (0, 0, -3.1))[2] == pytest.approx(2 * math.pi - 6.2)


@given(x=coord, y=coord, yaw=angle, ox=coord, oy=coord, oyaw=angle, bx=coord, by=coord, byaw=angle)
def test_the_window_error_ignores_where_each_frame_starts(x, y, yaw, ox, oy, oyaw, bx, by, byaw) -> None:
    """Odometry and ground truth live in frames offset by any fixed transform: the same motion has no error."""

    def in_frame(p):
        c, s = math.cos(oyaw), math.sin(oyaw)
        return (ox + c * p[0] - s * p[1], oy + s * p[0] + c * p[1], p[2] + oyaw)

    a, b = (x, y, yaw), (bx, by, byaw)
    err = motion_error(a, b, in_frame(a), in_frame(b), path_m=1.0, turned_rad=0.0)
    assert err.position_m == pytest.approx(0, abs=1e-9) and err.yaw_rad == pytest.approx(0, abs=1e-9)
    assert err.within(0.05, 0.03, 0.03)


def test_the_window_error_measures_disagreement_against_path_and_turning() -> None:
    err = motion_error((0, 0, 0), (1.0, 0, 0.5), (5, 5, 0), (5.9, 5, 0.45), path_m=1.0, turned_rad=0.5)
    assert err.position_m == pytest.approx(0.1) and err.yaw_rad == pytest.approx(0.05)
    assert not err.within(0.05, 0.03, 0.03)  # 10 cm > 5 % of 1 m + 3 cm
    assert err.within(0.05, 0.1, 0.03)


def test_interpolation_takes_the_short_arc() -> None:
    assert interpolate((0, 0, 3.1), (2, 4, -3.1), 0.5) == pytest.approx((1, 2, 3.1 + (2 * math.pi - 6.2) / 2))


def test_memory_growth_compares_medians_of_first_and_last_samples() -> None:
    assert growth_percent([100, 300, 100, 100, 110, 110, 500, 110]) == pytest.approx(10.0)
    assert growth_percent([100]) == 0.0
    assert growth_percent([100, 90]) == pytest.approx(-10.0)


def test_the_scripted_drive_is_figure_eights_with_quiet_stops() -> None:
    assert drive_command(0) == (0.5, 0.5)
    assert drive_command(LOOP_NS + SEC) == (0.5, -0.5)
    assert drive_command(10 * LOOP_NS + 1) is None  # the publisher goes quiet: the controller must brake
    assert drive_command(10 * LOOP_NS + STOP_NS) == (0.5, 0.5)
