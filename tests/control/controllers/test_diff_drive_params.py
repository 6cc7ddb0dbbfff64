"""diff_drive_controller parameters: the tutorial YAML loads as written; every bad value is quoted and named."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from diffctl.control.controllers.diff_drive_params import DiffDriveParams
from diffctl.control.math.speed_limiter import SpeedLimiter
from diffctl.errors import ParameterError
from diffctl.ros_args import load_params_file

REPO = Path(__file__).resolve().parents[3]
TUTORIAL_YAML = REPO / "config" / "diff_drive_controller.yaml"
BASE = {"left_wheel_names": ["l"], "right_wheel_names": ["r"], "wheel_separation": 0.3, "wheel_radius": 0.04}


def build(**overrides):
    return DiffDriveParams.from_params({**BASE, **overrides}, "ddc")


def test_tutorial_yaml_loads_as_written():
    flat = load_params_file(TUTORIAL_YAML, "diffbot_base_controller")
    p, warnings = DiffDriveParams.from_params(flat, "diffbot_base_controller")
    assert p.left_wheel_names == ("base_link_to_left_wheel",)
    assert p.right_wheel_names == ("base_link_to_right_wheel",)
    assert (p.wheel_separation_m, p.wheel_radius_m) == (0.3, 0.04)
    assert (p.odom_frame_id, p.base_frame_id) == ("odom", "base_footprint")
    assert p.open_loop and p.enable_odom_tf and p.publish_rate_hz == 50.0 and p.cmd_vel_timeout_s == 0.5
    assert p.pose_covariance_diagonal == (0.001, 0.001, 0.0, 0.0, 0.0, 0.01)
    assert (p.linear.min_velocity, p.linear.max_velocity, p.linear.max_acceleration) == (-1.0, 1.0, 1.0)
    assert math.isnan(p.linear.max_jerk) and math.isnan(p.linear.min_jerk)
    # Jazzy declares angular.z.min_acceleration and never reads it: the reverse bound stays unset (NaN, which
    # the limiter takes as -max_acceleration); has_*_limits: true is the default; so no warning at all.
    assert math.isnan(p.angular.max_acceleration_reverse)
    assert warnings == []
    lim = SpeedLimiter(p.linear)
    assert lim.limit(5.0, 0.0, 0.0, 0.05) == pytest.approx(0.05)  # 1 m/s² at 20 Hz


def test_defaults_follow_the_reference_table():
    p, warnings = build()
    assert warnings == []
    assert p.base_frame_id == "base_link" and p.odom_frame_id == "odom"
    assert (p.cmd_vel_timeout_s, p.publish_rate_hz, p.velocity_rolling_window_size) == (0.5, 50.0, 10)
    assert p.position_feedback and not p.open_loop and p.enable_odom_tf and not p.publish_limited_velocity
    assert p.tf_frame_prefix_enable and p.tf_frame_prefix == ""
    assert all(math.isnan(getattr(p.linear, f)) for f in p.linear.__dataclass_fields__)
    assert p.feedback_interface == "position"


def test_min_acceleration_is_accepted_and_ignored_as_in_jazzy():
    p, warnings = build(**{"linear.x.min_acceleration": 1.5, "angular.z.min_acceleration": -0.5,
                           "angular.z.max_acceleration": 2.0})
    assert warnings == []
    assert math.isnan(p.linear.max_acceleration_reverse) and math.isnan(p.angular.max_acceleration_reverse)
    assert SpeedLimiter(p.angular).limit(-5.0, 0.0, 0.0, 0.1) == pytest.approx(-0.2)  # -max_acceleration


def test_has_limits_warns_only_when_false():
    _, warnings = build(**{"linear.x.has_velocity_limits": True, "angular.z.has_jerk_limits": True})
    assert warnings == []
    _, warnings = build(**{"angular.z.has_acceleration_limits": False})
    assert warnings == ["[deprecated] has_acceleration_limits parameter is deprecated, instead set the respective "
                        "limits to NAN"]


def test_multipliers_give_the_effective_geometry():
    p, _ = build(wheel_separation_multiplier=2, left_wheel_radius_multiplier=0.5, right_wheel_radius_multiplier=1.5)
    assert (p.effective_wheel_separation_m, p.left_wheel_radius_m, p.right_wheel_radius_m) == pytest.approx(
        (0.6, 0.02, 0.06)
    )


def test_frame_prefix_rules():
    p, _ = build()
    assert p.frame_prefix("/") == ""
    assert p.frame_prefix("/robot1") == "robot1/"
    assert build(tf_frame_prefix="/car/")[0].frame_prefix("/robot1") == "car/"
    assert build(tf_frame_prefix_enable=False)[0].frame_prefix("/robot1") == ""


def test_has_limits_false_switches_a_group_off_with_a_warning():
    p, warnings = build(**{"linear.x.max_velocity": 1.0, "linear.x.has_velocity_limits": False})
    assert math.isnan(p.linear.max_velocity)
    assert any("has_velocity_limits parameter is deprecated" in w for w in warnings)


def test_removed_and_unknown_keys_warn():
    _, warnings = build(wheels_per_side=1, use_stamped_vel=False, wheel_seperation=0.3)
    text = "\n".join(warnings)
    assert "wheels_per_side" in text and "removed in Jazzy" in text
    assert "TwistStamped" in text
    assert "'ddc.wheel_seperation'" in text and "did you mean 'wheel_separation'" in text


@pytest.mark.parametrize(
    ("overrides", "field", "quoted"),
    [
        ({"wheel_radius": 0.0}, "ddc.wheel_radius", "0 must be > 0"),
        ({"wheel_radius": -0.04}, "ddc.wheel_radius", "-0.04"),
        ({"wheel_separation": "wide"}, "ddc.wheel_separation", "'wide' is not a number"),
        ({"wheel_separation": math.nan}, "ddc.wheel_separation", "nan"),
        ({"wheel_separation": math.inf}, "ddc.wheel_separation", "inf"),
        ({"wheel_separation": True}, "ddc.wheel_separation", "True is not a number"),
        ({"left_wheel_radius_multiplier": 0}, "ddc.left_wheel_radius_multiplier", "0 must be > 0"),
        ({"left_wheel_names": []}, "ddc.left_wheel_names", "[] must not be empty"),
        ({"left_wheel_names": "l"}, "ddc.left_wheel_names", "'l' is not a list (string_array)"),
        ({"left_wheel_names": ["a", "a"], "right_wheel_names": ["r", "s"]}, "ddc.left_wheel_names", "'a'"),
        ({"right_wheel_names": ["r", "s"]}, "ddc.right_wheel_names", "has 2 wheel(s)"),
        ({"right_wheel_names": ["l"]}, "ddc.right_wheel_names", "'l' is listed on both sides"),
        ({"cmd_vel_timeout": -1}, "ddc.cmd_vel_timeout", "-1 must be ≥ 0"),
        ({"publish_rate": 0}, "ddc.publish_rate", "0 must be > 0"),
        ({"velocity_rolling_window_size": 0}, "ddc.velocity_rolling_window_size", "0 must be within [1, 100000]"),
        ({"velocity_rolling_window_size": 2.5}, "ddc.velocity_rolling_window_size", "2.5 is not an integer"),
        ({"open_loop": "yes"}, "ddc.open_loop", "'yes' is not a bool"),
        ({"pose_covariance_diagonal": [0.1] * 5}, "ddc.pose_covariance_diagonal", "has 5 entries, expected 6"),
        ({"twist_covariance_diagonal": [0, 0, 0, 0, 0, -1]}, "ddc.twist_covariance_diagonal", "contains -1.0"),
        ({"base_frame_id": ""}, "ddc.base_frame_id", "'' must not be empty"),
        ({"base_frame_id": "odom"}, "ddc.base_frame_id", "'odom' is also odom_frame_id"),
        ({"linear.x.max_velocity": "fast"}, "ddc.linear.x.max_velocity", "'fast' is not a number"),
        ({"linear.x.max_velocity": 1.0, "linear.x.min_velocity": 2.0}, "ddc.linear.x.min_velocity", "2.0"),
        ({"linear.x.max_acceleration": -1.0}, "ddc.linear.x.max_acceleration", "-1.0 must be ≥ 0"),
        ({"linear.x.max_deceleration": 2.0}, "ddc.linear.x.max_deceleration", "2.0 must be ≤ 0"),
        ({"angular.z.max_acceleration_reverse": 1.0}, "ddc.angular.z.max_acceleration_reverse", "1.0 must be ≤ 0"),
        ({"angular.z.min_jerk": 0.5}, "ddc.angular.z.min_jerk", "0.5 must be ≤ 0"),
        ({"linear.x.has_jerk_limits": "no"}, "ddc.linear.x.has_jerk_limits", "'no' is not a bool"),
    ],
)
def test_bad_values_are_quoted_and_named(overrides, field, quoted):
    with pytest.raises(ParameterError) as e:
        build(**overrides)
    assert e.value.field == field
    assert quoted in str(e.value)
    assert str(e.value).startswith(field + ": ")
