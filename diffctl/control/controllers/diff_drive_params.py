"""Every parameter of diff_drive_controller/DiffDriveController (Jazzy), declared once and validated into a dataclass.

`DECLS` is diff_drive_controller's `src/diff_drive_controller_parameter.yaml` as a table (ros-controls/
ros2_controllers, branch jazzy, v4.42.1 / commit ed360c9, read through the reference notes): type, default,
description, validation (nothing is read-only there). The same table declares the parameters on the
controller's node (so `param list/describe` show what the real controller declares) and validates the values
`DiffDriveParams.from_params` builds the dataclass from; diffctl's checks beyond the YAML's (`also`: distinct
wheel names, positive multipliers and rate, covariances of six entries ≥ 0, …) refuse what would break the
controller later, and the rules between values (wheel lists of equal length, distinct frames, consistent limits)
follow.

Defaults are the reference's: base_frame_id "base_link", cmd_vel_timeout 0.5 s (0 disables it), publish_rate
50 Hz, every limit NaN (off).
Deprecated keys load, as Jazzy loads them:
  - `<axis>.has_velocity_limits` / `has_acceleration_limits` / `has_jerk_limits` (default true): false switches
    that group off, whatever numbers the group's limits hold (e.g. `max_jerk: 0.0`), with Jazzy's
    "[deprecated] … parameter is deprecated" warning; true is the default and says nothing;
  - `<axis>.min_acceleration`: declared (default NaN) and never read, as in Jazzy — it is not a reverse limit.
Keys removed before Jazzy (`wheels_per_side`, `use_stamped_vel`) are ignored with a warning saying why.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from diffctl.control.controllers.param_decl import (
    Check,
    ParamDecl,
    read_declared,
    table,
    unknown_key_warnings,
)
from diffctl.control.math.speed_limiter import LimitError, SpeedLimiter, SpeedLimits
from diffctl.errors import ParameterError

NAN = math.nan
AXES = ("linear.x", "angular.z")
_AXIS_UNITS = {"linear.x": ("m/s", "m/s²", "m/s³"), "angular.z": ("rad/s", "rad/s²", "rad/s³")}

# (name, sign the value must have when set: +1 ≥ 0, -1 ≤ 0, 0 any, index into the axis units)
_LIMIT_FIELDS: tuple[tuple[str, int, int], ...] = (
    ("max_velocity", 0, 0),
    ("min_velocity", 0, 0),
    ("max_acceleration", +1, 1),
    ("max_acceleration_reverse", -1, 1),
    ("max_deceleration", -1, 1),
    ("max_deceleration_reverse", +1, 1),
    ("max_jerk", +1, 2),
    ("min_jerk", -1, 2),
)
_GROUPS = {
    "has_velocity_limits": ("min_velocity", "max_velocity"),
    "has_acceleration_limits": (
        "max_acceleration",
        "max_acceleration_reverse",
        "max_deceleration",
        "max_deceleration_reverse",
    ),
    "has_jerk_limits": ("min_jerk", "max_jerk"),
}
_REMOVED = {
    "wheels_per_side": "removed in Jazzy: the number of wheels per side is the length of left_wheel_names",
    "use_stamped_vel": "removed in Jazzy: ~/cmd_vel only accepts geometry_msgs/msg/TwistStamped",
}
_POSITIVE = (Check("gt", (0.0,)),)


_DEPRECATED_FLAG = "deprecated, set the respective limits to ``.NAN`` for deactivation"
_AXIS_TEXT = {  # (linear.x, angular.z) descriptions; the velocity and jerk limits have none
    "max_acceleration": ("Maximum acceleration in forward direction.", "Maximum acceleration in positive direction."),
    "max_deceleration": ("Maximum deceleration in forward direction.", "Maximum deceleration in positive direction."),
    "max_acceleration_reverse": (
        "Maximum acceleration in reverse direction. If not set, -max_acceleration will be used.",
        "Maximum acceleration in negative direction. If not set, -max_acceleration will be used.",
    ),
    "max_deceleration_reverse": (
        "Maximum deceleration in reverse direction. If not set, -max_deceleration will be used.",
        "Maximum deceleration in negative direction. If not set, -max_deceleration will be used.",
    ),
}
_AXIS_ORDER = ("max_velocity", "min_velocity", "max_acceleration", "max_deceleration", "min_acceleration",
               "max_acceleration_reverse", "max_deceleration_reverse", "max_jerk", "min_jerk")
_GT_EQ_OR_NAN = (Check("control_filters::gt_eq_or_nan", (0.0,)),)
_LT_EQ_OR_NAN = (Check("control_filters::lt_eq_or_nan", (0.0,)),)


def _axis_decls(axis: str) -> list[ParamDecl]:
    out = [ParamDecl(f"{axis}.{flag}", "bool", True, _DEPRECATED_FLAG) for flag in _GROUPS]
    signs = {name: sign for name, sign, _unit in _LIMIT_FIELDS}
    for name in _AXIS_ORDER:
        if name == "min_acceleration":
            out.append(ParamDecl(f"{axis}.{name}", "double", NAN, "deprecated, use max_deceleration"))
            continue
        text = _AXIS_TEXT.get(name, ("", ""))[0 if axis == "linear.x" else 1]
        checks = _GT_EQ_OR_NAN if signs[name] > 0 or name == "max_velocity" else _LT_EQ_OR_NAN
        out.append(ParamDecl(f"{axis}.{name}", "double", NAN, text, checks=checks))
    return out


_COVARIANCE = (Check("size_eq", (6,)), Check("lower_element_bounds", (0.0,)))
_NOT_EMPTY = (Check("not_empty", ()),)
# diff_drive_controller_parameter.yaml, in its order; `also` holds diffctl's checks beyond the YAML's.
DECLS: dict[str, ParamDecl] = table(
    [
        ParamDecl("left_wheel_names", "string_array", [], "Names of the left side wheels' joints", checks=_NOT_EMPTY,
                  also=(Check("unique", ()),)),
        ParamDecl("right_wheel_names", "string_array", [], "Names of the right side wheels' joints",
                  checks=_NOT_EMPTY, also=(Check("unique", ()),)),
        ParamDecl("wheel_separation", "double", 0.0,
                  "Shortest distance between the left and right wheels. If this parameter is wrong, the robot will "
                  "not behave correctly in curves.", checks=_POSITIVE),
        ParamDecl("wheel_radius", "double", 0.0,
                  "Radius of a wheel, i.e., wheels size, used for transformation of linear velocity into wheel "
                  "rotations. If this parameter is wrong the robot will move faster or slower than expected.",
                  checks=_POSITIVE),
        ParamDecl("wheel_separation_multiplier", "double", 1.0,
                  "Correction factor when the actual wheel separation differs from the nominal value in the "
                  "``wheel_separation`` parameter.", also=_POSITIVE),
        ParamDecl("left_wheel_radius_multiplier", "double", 1.0,
                  "Correction factor when radius of left wheels differs from the nominal value in "
                  "``wheel_radius`` parameter.", also=_POSITIVE),
        ParamDecl("right_wheel_radius_multiplier", "double", 1.0,
                  "Correction factor when radius of right wheels differs from the nominal value in "
                  "``wheel_radius`` parameter.", also=_POSITIVE),
        ParamDecl("tf_frame_prefix_enable", "bool", True, "Enables or disables appending tf_prefix to tf frame id's."),
        ParamDecl("tf_frame_prefix", "string", "",
                  "(optional) Prefix to be appended to the tf frames, will be added to odom_id and base_frame_id "
                  "before publishing. If the parameter is empty, controller's namespace will be used."),
        ParamDecl("odom_frame_id", "string", "odom",
                  "Name of the frame for odometry. This frame is parent of ``base_frame_id`` when controller "
                  "publishes odometry.", also=_NOT_EMPTY),
        ParamDecl("base_frame_id", "string", "base_link",
                  "Name of the robot's base frame that is child of the odometry frame.", also=_NOT_EMPTY),
        ParamDecl("pose_covariance_diagonal", "double_array", [0.0] * 6,
                  "Odometry covariance for the encoder output of the robot for the pose. These values should be "
                  "tuned to your robot's sample odometry data, but these values are a good place to start: "
                  "``[0.001, 0.001, 0.001, 0.001, 0.001, 0.01]``.", also=_COVARIANCE),
        ParamDecl("twist_covariance_diagonal", "double_array", [0.0] * 6,
                  "Odometry covariance for the encoder output of the robot for the speed. These values should be "
                  "tuned to your robot's sample odometry data, but these values are a good place to start: "
                  "``[0.001, 0.001, 0.001, 0.001, 0.001, 0.01]``.", also=_COVARIANCE),
        ParamDecl("open_loop", "bool", False,
                  "If set to true the odometry of the robot will be calculated from the commanded values and not "
                  "from feedback."),
        ParamDecl("position_feedback", "bool", True, "Is there position feedback from hardware."),
        ParamDecl("enable_odom_tf", "bool", True,
                  "Publish transformation between ``odom_frame_id`` and ``base_frame_id``."),
        ParamDecl("cmd_vel_timeout", "double", 0.5,
                  "Timeout in seconds after which a command received on the ``cmd_vel`` topic is considered stale. "
                  "A value of 0.0 disables the timeout.", also=(Check("gt_eq", (0.0,)),)),
        ParamDecl("publish_limited_velocity", "bool", False, "Publish limited velocity value."),
        ParamDecl("velocity_rolling_window_size", "int", 10,
                  "Size of the rolling window for calculation of mean velocity use in odometry.",
                  also=(Check("bounds", (1, 100_000)),)),
        ParamDecl("publish_rate", "double", 50.0, "Publishing rate (Hz) of the odometry and TF messages.",
                  also=_POSITIVE),
        *_axis_decls("linear.x"),
        *_axis_decls("angular.z"),
    ]
)
# Parameters a running controller takes on its next update (the rest wait for the next configure).
RUNTIME = frozenset(
    {"cmd_vel_timeout", "wheel_separation_multiplier", "left_wheel_radius_multiplier", "right_wheel_radius_multiplier"}
    | {k for k in DECLS if k.startswith(AXES)}
)


@dataclass(frozen=True)
class DiffDriveParams:
    """diff_drive_controller's parameters; attribute names carry units, the ROS names are in the docstrings."""

    left_wheel_names: tuple[str, ...]
    right_wheel_names: tuple[str, ...]
    wheel_separation_m: float  # wheel_separation
    wheel_radius_m: float  # wheel_radius
    wheel_separation_multiplier: float = 1.0
    left_wheel_radius_multiplier: float = 1.0
    right_wheel_radius_multiplier: float = 1.0
    tf_frame_prefix_enable: bool = True
    tf_frame_prefix: str = ""
    odom_frame_id: str = "odom"
    base_frame_id: str = "base_link"
    pose_covariance_diagonal: tuple[float, ...] = (0.0,) * 6
    twist_covariance_diagonal: tuple[float, ...] = (0.0,) * 6
    open_loop: bool = False
    position_feedback: bool = True
    enable_odom_tf: bool = True
    cmd_vel_timeout_s: float = 0.5  # cmd_vel_timeout; 0 disables the timeout
    publish_limited_velocity: bool = False
    velocity_rolling_window_size: int = 10
    publish_rate_hz: float = 50.0  # publish_rate
    linear: SpeedLimits = field(default_factory=SpeedLimits)  # linear.x.*
    angular: SpeedLimits = field(default_factory=SpeedLimits)  # angular.z.*

    # --- derived ---------------------------------------------------------------------------------------------
    @property
    def effective_wheel_separation_m(self) -> float:
        return self.wheel_separation_multiplier * self.wheel_separation_m

    @property
    def left_wheel_radius_m(self) -> float:
        return self.left_wheel_radius_multiplier * self.wheel_radius_m

    @property
    def right_wheel_radius_m(self) -> float:
        return self.right_wheel_radius_multiplier * self.wheel_radius_m

    @property
    def feedback_interface(self) -> str:
        return "position" if self.position_feedback else "velocity"

    def frame_prefix(self, namespace: str) -> str:
        """The tf prefix: tf_frame_prefix, or the node namespace when it is empty; "" for the root namespace."""
        if not self.tf_frame_prefix_enable:
            return ""
        prefix = self.tf_frame_prefix or namespace or ""
        prefix = prefix.lstrip("/")
        if prefix and not prefix.endswith("/"):
            prefix += "/"
        return prefix

    # --- construction ----------------------------------------------------------------------------------------
    @classmethod
    def from_params(
        cls, params: Mapping[str, Any], controller: str = "diff_drive_controller"
    ) -> tuple[DiffDriveParams, list[str]]:
        """Validate `params` (flattened) into DiffDriveParams; returns it with the warnings to log."""
        values = read_declared(DECLS, params, controller)
        warnings: list[str] = []
        p = cls.from_values(values, controller, given=params.keys(), warnings=warnings)
        for key, why in _REMOVED.items():
            if key in params:
                warnings.append(f"parameter '{controller}.{key}' is ignored: {why}")
        if params.get("use_stamped_vel") is False:
            warnings.append("use_stamped_vel: false has no effect: publish TwistStamped to ~/cmd_vel")
        warnings.extend(unknown_key_warnings(DECLS, params, controller, also_known=_REMOVED))
        return p, warnings

    @classmethod
    def from_values(
        cls, v: Mapping[str, Any], controller: str, *, given: Any = (), warnings: list[str] | None = None
    ) -> DiffDriveParams:
        """Build from typed values (as `read_declared` returns them) and check the rules between values."""
        warnings = [] if warnings is None else warnings
        left, right = tuple(v["left_wheel_names"]), tuple(v["right_wheel_names"])
        if len(left) != len(right):
            raise ParameterError(
                f"{list(right)!r} has {len(right)} wheel(s) but left_wheel_names {list(left)!r} has {len(left)}",
                field=f"{controller}.right_wheel_names",
                hint="give the same number of wheels on both sides",
            )
        both = sorted(set(left) & set(right))
        if both:
            raise ParameterError(f"joint {both[0]!r} is listed on both sides", field=f"{controller}.right_wheel_names")
        if v["odom_frame_id"] == v["base_frame_id"]:
            raise ParameterError(
                f"{v['base_frame_id']!r} is also odom_frame_id: the frames must differ",
                field=f"{controller}.base_frame_id",
            )
        return cls(
            left_wheel_names=left,
            right_wheel_names=right,
            wheel_separation_m=v["wheel_separation"],
            wheel_radius_m=v["wheel_radius"],
            wheel_separation_multiplier=v["wheel_separation_multiplier"],
            left_wheel_radius_multiplier=v["left_wheel_radius_multiplier"],
            right_wheel_radius_multiplier=v["right_wheel_radius_multiplier"],
            tf_frame_prefix_enable=v["tf_frame_prefix_enable"],
            tf_frame_prefix=v["tf_frame_prefix"],
            odom_frame_id=v["odom_frame_id"],
            base_frame_id=v["base_frame_id"],
            pose_covariance_diagonal=tuple(v["pose_covariance_diagonal"]),
            twist_covariance_diagonal=tuple(v["twist_covariance_diagonal"]),
            open_loop=v["open_loop"],
            position_feedback=v["position_feedback"],
            enable_odom_tf=v["enable_odom_tf"],
            cmd_vel_timeout_s=v["cmd_vel_timeout"],
            publish_limited_velocity=v["publish_limited_velocity"],
            velocity_rolling_window_size=v["velocity_rolling_window_size"],
            publish_rate_hz=v["publish_rate"],
            linear=_axis_limits(v, "linear.x", controller, set(given), warnings),
            angular=_axis_limits(v, "angular.z", controller, set(given), warnings),
        )


def _axis_limits(v: Mapping[str, Any], axis: str, controller: str, given: set[str], warnings: list[str]) -> SpeedLimits:
    units = _AXIS_UNITS[axis]
    values = {name: v[f"{axis}.{name}"] for name, _s, _u in _LIMIT_FIELDS}

    # `<axis>.min_acceleration` is declared and never read (Jazzy's on_configure does not look at it).
    # has_*: false switches its group off before any number of the group is looked at, as Jazzy's
    # on_configure overwrites them with NaN, warning with its own words; true (the default) says nothing.
    for flag, group in _GROUPS.items():
        if v[f"{axis}.{flag}"]:
            continue
        warnings.append(f"[deprecated] {flag} parameter is deprecated, instead set the respective limits to NAN")
        for name in group:
            values[name] = NAN

    for name, sign, unit in _LIMIT_FIELDS:
        value, key = values[name], f"{controller}.{axis}.{name}"
        if sign > 0 and value < 0.0:
            raise ParameterError(f"{value!r} must be ≥ 0: it bounds the change from above ({units[unit]})", field=key)
        if sign < 0 and value > 0.0:
            raise ParameterError(
                f"{value!r} must be ≤ 0: it bounds the change from below ({units[unit]})",
                field=key,
                hint=f"a limit of magnitude {value:g} is written {-value!r}",
            )

    if math.isnan(values["max_acceleration"]) and any(
        not math.isnan(values[n]) for n in ("max_acceleration_reverse", "max_deceleration", "max_deceleration_reverse")
    ):
        warnings.append(f"{axis}: acceleration limits are off because {axis}.max_acceleration is .NAN")
    if math.isnan(values["max_velocity"]) and not math.isnan(values["min_velocity"]):
        warnings.append(f"{axis}: velocity limits are off because {axis}.max_velocity is .NAN")
    if math.isnan(values["max_jerk"]) and not math.isnan(values["min_jerk"]):
        warnings.append(f"{axis}: jerk limits are off because {axis}.max_jerk is .NAN")

    limits = SpeedLimits(**values)
    try:
        SpeedLimiter(limits)
    except LimitError as e:
        raise ParameterError(e.message, field=f"{controller}.{axis}.{e.field}") from None
    return limits
