"""The limits of one joint and the per-interface values a limiter reads and bounds (joint_limits' data types).

Units are the joint's own: positions in rad (revolute, continuous) or m (prismatic), velocities per second,
accelerations and decelerations per second², jerk per second³, effort in N·m or N. A limit left NaN is not set:
every comparison with it is false, so it bounds nothing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

_NAN = math.nan
_DBL_MAX = 1.7976931348623157e308  # std::numeric_limits<double>::max(): "disabled" bounds are this, not inf


def _num(value: float) -> str:
    """A double as a C++ stream prints it (6 significant digits)."""
    return format(value, ".6g")


@dataclass(slots=True)
class JointLimits:
    """A joint's hard limits: URDF `<limit lower upper velocity effort>` narrowed by its `<ros2_control>`
    interfaces' `min`/`max` (joint_limits_urdf.py), each group switched on by its `has_*` flag."""

    min_position: float = _NAN
    max_position: float = _NAN
    max_velocity: float = _NAN
    max_acceleration: float = _NAN
    max_deceleration: float = _NAN
    max_jerk: float = _NAN
    max_effort: float = _NAN
    has_position_limits: bool = False
    has_velocity_limits: bool = False
    has_acceleration_limits: bool = False
    has_deceleration_limits: bool = False
    has_jerk_limits: bool = False
    has_effort_limits: bool = False
    angle_wraparound: bool = False

    def disable_all_limits(self) -> None:
        self.has_position_limits = self.has_velocity_limits = self.has_acceleration_limits = False
        self.has_deceleration_limits = self.has_jerk_limits = self.has_effort_limits = False
        self.min_position = -_DBL_MAX
        self.max_position = self.max_velocity = self.max_acceleration = _DBL_MAX
        self.max_deceleration = self.max_jerk = self.max_effort = _DBL_MAX

    def to_string(self) -> str:
        """The multi-line summary the resource manager logs for a joint's limiter."""

        def flag(on: bool) -> str:
            return "true" if on else "false"

        rows = [
            f"  has position limits: {flag(self.has_position_limits)} [{_num(self.min_position)}, "
            f"{_num(self.max_position)}]",
            f"  has velocity limits: {flag(self.has_velocity_limits)} [{_num(self.max_velocity)}]",
            f"  has acceleration limits: {flag(self.has_acceleration_limits)} [{_num(self.max_acceleration)}]",
            f"  has deceleration limits: {flag(self.has_deceleration_limits)} [{_num(self.max_deceleration)}]",
            f"  has jerk limits: {flag(self.has_jerk_limits)} [{_num(self.max_jerk)}]",
            f"  has effort limits: {flag(self.has_effort_limits)} [{_num(self.max_effort)}]",
            f"  angle wraparound: {flag(self.angle_wraparound)}",
        ]
        return "\n".join(rows)


@dataclass
class SoftJointLimits:
    """URDF `<safety_controller soft_lower_limit soft_upper_limit k_position k_velocity>`."""

    min_position: float = _NAN
    max_position: float = _NAN
    k_position: float = _NAN
    k_velocity: float = _NAN

    def to_string(self) -> str:
        return (
            f"  soft position limits: [{_num(self.min_position)}, {_num(self.max_position)}]\n"
            f"  k-position: [{_num(self.k_position)}]\n"
            f"  k-velocity: [{_num(self.k_velocity)}]\n"
        )


@dataclass(slots=True)
class JointControlInterfacesData:
    """One joint's values on its position/velocity/effort/acceleration/jerk interfaces; None where it has none
    (or, for commands, where no controller claims it)."""

    joint_name: str = ""
    position: float | None = None
    velocity: float | None = None
    effort: float | None = None
    acceleration: float | None = None
    jerk: float | None = None

    def has_data(self) -> bool:
        return not (
            self.position is None
            and self.velocity is None
            and self.effort is None
            and self.acceleration is None
            and self.jerk is None
        )

    def copy(self) -> JointControlInterfacesData:
        return JointControlInterfacesData(
            self.joint_name, self.position, self.velocity, self.effort, self.acceleration, self.jerk
        )

    def to_string(self) -> str:
        parts = [f"Joint: '{self.joint_name}'"]
        for f in fields(self)[1:]:
            value = getattr(self, f.name)
            if value is not None:
                parts.append(f"{f.name}: {value:f}")
        return ", ".join(parts)


INTERFACE_KINDS = ("position", "velocity", "effort", "acceleration")  # the command interfaces limits apply to


def limiter_data_string(joint: str, actual: JointControlInterfacesData, command: JointControlInterfacesData,
                        limited: JointControlInterfacesData) -> str:
    """The (actual, command, limited) triple as the resource manager's limiting error prints it."""
    return (
        f"Joint: '{joint}', (actual: [{actual.to_string()}], command: [{command.to_string()}], "
        f"limited: [{limited.to_string()}])"
    )
