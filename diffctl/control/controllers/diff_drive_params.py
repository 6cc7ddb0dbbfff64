"""Every parameter of diff_drive_controller/DiffDriveController (Jazzy tip), validated once into a frozen dataclass.

Built from the controller's flattened parameters (`linear.x.max_velocity`, …) by `DiffDriveParams.from_params`,
which returns the parameters and the warnings to log (deprecated and removed keys, unknown keys, limits that
have no effect). Defaults are the reference's: base_frame_id "base_link", cmd_vel_timeout 0.5 s (0 disables
it), publish_rate 50 Hz, every limit NaN (off).

Deprecated keys still load, with a warning, as the tip does:
  - `<axis>.has_velocity_limits` / `has_acceleration_limits` / `has_jerk_limits`: false switches that group off
    (sets it to NaN); true has no effect;
  - `<axis>.min_acceleration`: the old symmetric lower bound on acceleration; it becomes
    `max_acceleration_reverse` (which `max_deceleration` then defaults to) unless those are given.
Keys removed before Jazzy (`wheels_per_side`, `use_stamped_vel`) are ignored with a warning saying why.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from diffctl.control.controllers.param_values import ParamReader
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
        r = ParamReader(params, controller)
        warnings: list[str] = []

        left = r.str_list("left_wheel_names", [], non_empty=True)
        right = r.str_list("right_wheel_names", [], non_empty=True)
        if len(left) != len(right):
            raise r.error(
                "right_wheel_names",
                f"{list(right)!r} has {len(right)} wheel(s) but left_wheel_names {list(left)!r} has {len(left)}",
                "give the same number of wheels on both sides",
            )
        both = sorted(set(left) & set(right))
        if both:
            raise r.error("right_wheel_names", f"joint {both[0]!r} is listed on both sides")

        kw: dict[str, Any] = {
            "left_wheel_names": left,
            "right_wheel_names": right,
            "wheel_separation_m": r.float("wheel_separation", 0.0, gt=0.0, what="distance between the wheels in m"),
            "wheel_radius_m": r.float("wheel_radius", 0.0, gt=0.0, what="wheel radius in m"),
            "wheel_separation_multiplier": r.float("wheel_separation_multiplier", 1.0, gt=0.0),
            "left_wheel_radius_multiplier": r.float("left_wheel_radius_multiplier", 1.0, gt=0.0),
            "right_wheel_radius_multiplier": r.float("right_wheel_radius_multiplier", 1.0, gt=0.0),
            "tf_frame_prefix_enable": r.bool("tf_frame_prefix_enable", True),
            "tf_frame_prefix": r.str("tf_frame_prefix", ""),
            "odom_frame_id": r.str("odom_frame_id", "odom", non_empty=True),
            "base_frame_id": r.str("base_frame_id", "base_link", non_empty=True),
            "pose_covariance_diagonal": r.float_list("pose_covariance_diagonal", [0.0] * 6, length=6, ge=0.0),
            "twist_covariance_diagonal": r.float_list("twist_covariance_diagonal", [0.0] * 6, length=6, ge=0.0),
            "open_loop": r.bool("open_loop", False),
            "position_feedback": r.bool("position_feedback", True),
            "enable_odom_tf": r.bool("enable_odom_tf", True),
            "cmd_vel_timeout_s": r.float("cmd_vel_timeout", 0.5, ge=0.0, what="seconds; 0 disables the timeout"),
            "publish_limited_velocity": r.bool("publish_limited_velocity", False),
            "velocity_rolling_window_size": r.int("velocity_rolling_window_size", 10, ge=1, le=100_000),
            "publish_rate_hz": r.float("publish_rate", 50.0, gt=0.0, what="odometry and tf rate in Hz"),
        }
        if kw["odom_frame_id"] == kw["base_frame_id"]:
            raise r.error("base_frame_id", f"{kw['base_frame_id']!r} is also odom_frame_id: the frames must differ")
        for axis in AXES:
            kw[axis.split(".")[0]] = _axis_limits(r, axis, warnings)

        for key, why in _REMOVED.items():
            if r.has(key):
                warnings.append(f"parameter {r.field(key)!r} is ignored: {why}")
        if r.has("use_stamped_vel") and params["use_stamped_vel"] is False:
            warnings.append("use_stamped_vel: false has no effect: publish TwistStamped to ~/cmd_vel")
        warnings.extend(r.unknown_key_warnings())
        return cls(**kw), warnings


def _axis_limits(r: ParamReader, axis: str, warnings: list[str]) -> SpeedLimits:
    units = _AXIS_UNITS[axis]
    values: dict[str, float] = {}
    for name, sign, unit in _LIMIT_FIELDS:
        key = f"{axis}.{name}"
        value = r.float(key, NAN, allow_nan=True, allow_inf=True, what=f"{units[unit]}, or .NAN for no limit")
        raw = r.params.get(key)
        if sign > 0 and value < 0.0:
            raise r.error(key, f"{raw!r} must be ≥ 0: it bounds the change from above ({units[unit]})")
        if sign < 0 and value > 0.0:
            raise r.error(
                key,
                f"{raw!r} must be ≤ 0: it bounds the change from below ({units[unit]})",
                f"a limit of magnitude {value:g} is written {-value!r}",
            )
        values[name] = value

    old_min_key = f"{axis}.min_acceleration"
    old_min = r.float(old_min_key, NAN, allow_nan=True, le=0.0, what=f"{units[1]}, deprecated")
    if r.has(old_min_key):
        if math.isnan(values["max_acceleration_reverse"]):
            values["max_acceleration_reverse"] = old_min
            warnings.append(
                f"[deprecated] {r.field(old_min_key)} = {old_min!r} is used as {axis}.max_acceleration_reverse "
                f"(and max_deceleration when unset); rename it"
            )
        else:
            warnings.append(
                f"[deprecated] {r.field(old_min_key)} is ignored because {axis}.max_acceleration_reverse is set"
            )

    no_effect = []
    for flag, group in _GROUPS.items():
        key = f"{axis}.{flag}"
        enabled = r.bool(key, True)
        if not r.has(key):
            continue
        if enabled:
            no_effect.append(flag)
        else:
            warnings.append(f"[deprecated] {r.field(key)} = false switches these limits off: set them to .NAN")
            for name in group:
                values[name] = NAN
    if no_effect:
        warnings.append(
            f"[deprecated] {r.field(axis)}.{'/'.join(no_effect)}: true has no effect, a limit is on unless it is .NAN"
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
        raise ParameterError(e.message, field=r.field(f"{axis}.{e.field}")) from None
    return limits
