"""Pure math of the DiffDrive system: limits, wheel speeds, odometry; and its SDF parameters."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from diffctl.description.model import Plugin
from diffctl.errors import DescriptionError
from diffctl.sim.plugins.diff_drive import DiffDriveParams
from diffctl.sim.plugins.diff_drive_math import Limits, Odometry, limit_speed, wheel_speeds_rad_s


def test_wheel_speeds_for_straight_and_turning_motion() -> None:
    assert wheel_speeds_rad_s(0.5, 0.0, 0.3, 0.04) == pytest.approx((12.5, 12.5))
    left, right = wheel_speeds_rad_s(0.0, 1.0, 0.3, 0.04)
    assert (left, right) == pytest.approx((-3.75, 3.75))


def test_acceleration_limit_ramps_and_velocity_limit_clamps() -> None:
    lim = Limits(min_velocity=-1.0, max_velocity=1.0, min_acceleration=-2.0, max_acceleration=1.0)
    v0 = v1 = 0.0
    trace = []
    for _ in range(1500):
        v = limit_speed(5.0, v0, v1, 0.001, lim)
        v0, v1 = v, v0
        trace.append(v)
    assert trace[0] == pytest.approx(0.001) and trace[499] == pytest.approx(0.5)
    assert max(trace) == 1.0
    v = limit_speed(-5.0, 1.0, 1.0, 0.001, lim)
    assert v == pytest.approx(1.0 - 0.002)


@given(st.floats(-10, 10), st.floats(-3, 3), st.floats(-3, 3))
def test_limited_speed_never_leaves_the_bounds(target: float, v0: float, v1: float) -> None:
    lim = Limits(
        min_velocity=-1.0, max_velocity=2.0, min_acceleration=-1.0, max_acceleration=1.0, min_jerk=-5.0, max_jerk=5.0
    )
    v = limit_speed(target, v0, v1, 0.01, lim)
    assert -1.0 <= v <= 2.0


def test_odometry_of_a_quarter_circle() -> None:
    odo = Odometry(0.3, 0.04, window=1)
    r_turn = 1.0
    w = 0.5  # rad/s of the body
    v = w * r_turn
    wl, wr = wheel_speeds_rad_s(v, w, 0.3, 0.04)
    t = 0.0
    odo.update(0.0, 0.0, 0.0)
    while t < math.pi / 2 / w - 1e-9:
        t += 0.02
        odo.update(wl * t, wr * t, t)
    assert odo.heading_rad == pytest.approx(math.pi / 2, rel=1e-2)
    assert (odo.x_m, odo.y_m) == pytest.approx((1.0, 1.0), abs=0.02)
    assert odo.linear_m_s == pytest.approx(v) and odo.angular_rad_s == pytest.approx(w)


def plugin(**params: str) -> Plugin:
    return Plugin("gz::sim::systems::DiffDrive", "gz-sim-diff-drive-system", tuple(params.items()))


def test_params_defaults_as_gazebo_and_limits_mirror_min_from_max() -> None:
    p = DiffDriveParams.from_plugin(
        plugin(left_joint="l", right_joint="r", max_linear_acceleration="2"), "car", "chassis"
    )
    assert (p.wheel_separation_m, p.wheel_radius_m, p.odom_publish_frequency_hz) == (1.0, 0.2, 50.0)
    assert (p.topic, p.odom_topic, p.tf_topic) == ("/model/car/cmd_vel", "/model/car/odometry", "/model/car/tf")
    assert (p.frame_id, p.child_frame_id) == ("car/odom", "car/chassis")
    assert (p.linear.min_acceleration, p.linear.max_acceleration) == (-2.0, 2.0)
    assert p.linear.rate_limited and not p.angular.rate_limited


@pytest.mark.parametrize(
    "params, needle",
    [
        ({"left_joint": "l"}, "right_joint"),
        ({"left_joint": "l", "right_joint": "r", "wheel_radius": "-0.1"}, "'-0.1'"),
        ({"left_joint": "l", "right_joint": "r", "wheel_separation": "abc"}, "'abc'"),
        ({"left_joint": "l", "right_joint": "r", "max_linear_velocity": "nan"}, "'nan'"),
    ],
)
def test_bad_params_are_one_clear_error(params: dict[str, str], needle: str) -> None:
    with pytest.raises(DescriptionError, match=needle):
        DiffDriveParams.from_plugin(plugin(**params), "car", "chassis", "car.sdf")
