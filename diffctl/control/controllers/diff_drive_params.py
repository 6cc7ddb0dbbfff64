"""Every parameter of diff_drive_controller/DiffDriveController (Jazzy), declared once and validated into a dataclass.

`DECLS` is diff_drive_controller's `src/diff_drive_controller_parameter.yaml` as a table (ros-controls/
ros2_controllers, branch jazzy, v4.42.1 / commit ed360c9, read through the reference notes): type, default,
read_only, validation. The same table declares the parameters on the controller's node (so `param
describe` shows them) and validates the values `DiffDriveParams.from_params` builds the dataclass from; the
few rules beyond single values (wheel lists of equal length, distinct frames, consistent limits) follow.

Defaults are the reference's: base_frame_id "base_link", cmd_vel_timeout 0.5 s (0 disables it), publish_rate
50 Hz, every limit NaN (off). Read-only, as in the YAML: the wheel names, wheel_separation and wheel_radius.
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
    BASE_DECLS,
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
_NAMES = (Check("not_empty", ()), Check("unique", ()))


def _axis_decls(axis: str) -> list[ParamDecl]:
    units = _AXIS_UNITS[axis]
    out = [
        ParamDecl(f"{axis}.{flag}", "bool", True, "deprecated, set the respective limits to ``.NAN`` for deactivation")
        for flag in _GROUPS
    ]
    for name, _sign, unit in _LIMIT_FIELDS:
        out.append(ParamDecl(f"{axis}.{name}", "double", NAN, f"{name.replace('_', ' ')} in {units[unit]}; NaN: none."))
    out.append(
        ParamDecl(
            f"{axis}.min_acceleration",
            "double",
            NAN,
            "deprecated, use max_deceleration",
        )
    )
    return out


DECLS: dict[str, ParamDecl] = table(
    [
        *BASE_DECLS,
        ParamDecl("left_wheel_names", "string_array", [], "Joints of the left wheels.", True, _NAMES),
        ParamDecl("right_wheel_names", "string_array", [], "Joints of the right wheels.", True, _NAMES),
        ParamDecl("wheel_separation", "double", 0.0, "Distance between left and right wheels in m.", True, _POSITIVE),
        ParamDecl("wheel_radius", "double", 0.0, "Wheel radius in m.", True, _POSITIVE),
        ParamDecl(
            "wheel_separation_multiplier", "double", 1.0, "Correction factor of wheel_separation.", False, _POSITIVE
        ),
        ParamDecl(
            "left_wheel_radius_multiplier",
            "double",
            1.0,
            "Correction factor of the left wheels' radius.",
            False,
            _POSITIVE,
        ),
        ParamDecl(
            "right_wheel_radius_multiplier",
            "double",
            1.0,
            "Correction factor of the right wheels' radius.",
            False,
            _POSITIVE,
        ),
        ParamDecl("tf_frame_prefix_enable", "bool", True, "Prefix odom_frame_id and base_frame_id."),
        ParamDecl("tf_frame_prefix", "string", "", "The prefix; empty: the controller's namespace."),
        ParamDecl("odom_frame_id", "string", "odom", "Frame of the odometry.", False, (Check("not_empty", ()),)),
        ParamDecl(
            "base_frame_id",
            "string",
            "base_link",
            "The robot's base frame, child of odom_frame_id.",
            False,
            (Check("not_empty", ()),),
        ),
        ParamDecl(
            "pose_covariance_diagonal",
            "double_array",
            [0.0] * 6,
            "Diagonal of the odometry pose covariance.",
            False,
            (Check("size_eq", (6,)), Check("lower_element_bounds", (0.0,))),
        ),
        ParamDecl(
            "twist_covariance_diagonal",
            "double_array",
            [0.0] * 6,
            "Diagonal of the odometry twist covariance.",
            False,
            (Check("size_eq", (6,)), Check("lower_element_bounds", (0.0,))),
        ),
        ParamDecl("open_loop", "bool", False, "Odometry from the commands instead of wheel feedback."),
        ParamDecl("position_feedback", "bool", True, "Wheel feedback is position (else velocity)."),
        ParamDecl("enable_odom_tf", "bool", True, "Publish odom_frame_id → base_frame_id on /tf."),
        ParamDecl(
            "cmd_vel_timeout",
            "double",
            0.5,
            "Seconds after which a command is stale; 0 disables it.",
            False,
            (Check("gt_eq", (0.0,)),),
        ),
        ParamDecl("publish_limited_velocity", "bool", False, "Publish the limited command on ~/cmd_vel_out."),
        ParamDecl(
            "velocity_rolling_window_size",
            "int",
            10,
            "Samples averaged into the odometry twist.",
            False,
            (Check("bounds", (1, 100_000)),),
        ),
        ParamDecl("publish_rate", "double", 50.0, "Rate of ~/odom and /tf in Hz.", False, _POSITIVE),
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
