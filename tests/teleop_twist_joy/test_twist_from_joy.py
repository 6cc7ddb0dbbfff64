"""teleop_twist_joy's rule against upstream's own launch tests (test/*_joy_launch_test.py: each one's node
parameters, the Joy message it publishes and the Twist it expects), plus the stop-once rule and
inverted_reverse as teleop_twist_joy.cpp has them."""

from __future__ import annotations

import pytest

from diffctl.teleop_twist_joy.twist_from_joy import STOP, Settings, TeleopTwistJoy

DIFF = {"axis_linear.x": 1, "axis_angular.yaw": 0, "scale_linear.x": 2.0, "scale_angular.yaw": 3.0, "enable_button": 0}
TURBO = {"axis_linear.x": 1, "axis_angular.yaw": 0, "scale_linear.x": 1.0, "scale_linear_turbo.x": 2.0,
         "scale_angular.yaw": 1.0, "enable_button": 0, "enable_turbo_button": 1}
UPSTREAM = {
    "differential": (DIFF, [0.3, 0.4], [1], (0.8, 0, 0), (0, 0, 0.9)),
    "holonomic": ({"axis_linear.x": 1, "axis_linear.y": 2, "axis_angular.yaw": 0, "scale_linear.x": 1.0,
                   "scale_linear.y": 4.0, "scale_angular.yaw": 3.0, "enable_button": 0},
                  [0.3, 0.4, 0.5], [1], (0.4, 2.0, 0), (0, 0, 0.9)),
    "no_enable": ({**DIFF, "require_enable_button": True}, [0.3, 0.4], [0], (0, 0, 0), (0, 0, 0)),
    "no_require_enable": ({**DIFF, "require_enable_button": False}, [0.3, 0.4], [0], (0.8, 0, 0), (0, 0, 0.9)),
    "six_dof": ({"axis_linear.x": 1, "axis_linear.y": 2, "axis_linear.z": 3, "axis_angular.roll": 4,
                 "axis_angular.pitch": 5, "axis_angular.yaw": 0, "scale_linear.x": 1.0, "scale_linear.y": 4.0,
                 "scale_linear.z": 2.0, "scale_angular.roll": 3.0, "scale_angular.pitch": 2.0,
                 "scale_angular.yaw": 1.0, "enable_button": 0},
                [0.3, 0.4, 0.5, 0.6, 0.7, 0.8], [1], (0.4, 2.0, 1.2), (2.1, 1.6, 0.3)),
    "turbo_angular_enable": ({**TURBO, "scale_angular_turbo.yaw": 2.0}, [0.3, 0.4], [1, 1], (0.8, 0, 0), (0, 0, 0.6)),
    "only_turbo": ({**TURBO, "scale_angular_turbo.yaw": 3.0}, [0.3, 0.4], [0, 1], (0.8, 0, 0), (0, 0, 0.9)),
    "turbo_enable": ({**TURBO, "scale_angular_turbo.yaw": 3.0}, [0.3, 0.4], [1, 1], (0.8, 0, 0), (0, 0, 0.9)),
}


@pytest.mark.parametrize("case", list(UPSTREAM))
def test_upstream_launch_tests(case: str) -> None:
    params, axes, buttons, linear, angular = UPSTREAM[case]
    got = TeleopTwistJoy(Settings.from_values(params)).on_joy(axes, buttons)
    assert got is not None
    assert got.linear == pytest.approx(linear) and got.angular == pytest.approx(angular)


def test_release_stops_once_and_missing_axes_or_buttons_count_as_zero() -> None:
    teleop = TeleopTwistJoy(Settings.from_values(DIFF))
    assert teleop.on_joy([0.3, 0.4], [1]).linear == pytest.approx((0.8, 0, 0))
    assert teleop.on_joy([0.3, 0.4], [0]) == STOP
    assert teleop.on_joy([0.3, 0.4], [0]) is None
    assert teleop.on_joy([0.3, 0.4], []) is None  # no such button: not held
    assert teleop.on_joy([0.3], [1]).linear == pytest.approx((0.0, 0, 0))  # axis 1 absent
    assert teleop.on_joy([], [0]) == STOP


def test_defaults_and_inverted_reverse() -> None:
    teleop = TeleopTwistJoy(Settings.from_values({}))  # axis_linear.x 5, yaw 2, enable_button 5, scales 0.5
    axes = [0.0, 0.0, 0.6, 0.0, 0.0, -1.0]
    assert teleop.on_joy(axes, [0, 0, 0, 0, 0, 1]).linear[0] == pytest.approx(-0.5)
    assert teleop.on_joy(axes, [0, 0, 0, 0, 0, 1]).angular[2] == pytest.approx(0.3)
    inverted = TeleopTwistJoy(Settings.from_values({"inverted_reverse": True}))
    assert inverted.on_joy(axes, [0, 0, 0, 0, 0, 1]).angular[2] == pytest.approx(-0.3)  # backwards: yaw mirrored
    axes[5] = 1.0
    assert inverted.on_joy(axes, [0, 0, 0, 0, 0, 1]).angular[2] == pytest.approx(0.3)


def test_run_time_changes_reach_the_rule() -> None:
    settings = Settings.from_values(DIFF)
    teleop = TeleopTwistJoy(settings)
    settings.update("scale_linear.x", 1.0)
    settings.update("enable_button", 1)
    settings.update("frame", "ignored")
    assert teleop.on_joy([0.3, 0.4], [0, 1]).linear == pytest.approx((0.4, 0, 0))
