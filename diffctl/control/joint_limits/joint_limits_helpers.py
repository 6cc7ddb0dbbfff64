"""The bounds a joint's next command may take this period (joint_limits_helpers): pure functions of its limits,
its measured state and its previous command.

Each returns a (lower, upper) pair, never inverted. Comparisons follow C++'s std::min/max/clamp on purpose: a
NaN limit (one not set) or a NaN measurement leaves a bound where it was instead of raising, as in ros2_control.
"""

from __future__ import annotations

import math

from diffctl.control.joint_limits.joint_limits import JointLimits

POSITION_BOUNDS_TOLERANCE = 0.002
# Half a degree, or about 1 cm on a prismatic joint: a measured position this far past its bound is a fault.
OUT_OF_BOUNDS_EXCEPTION_TOLERANCE = 0.0087

_INF = math.inf


def cmax(a: float, b: float) -> float:
    """std::max: `a` unless a < b (so a NaN first argument is kept)."""
    return b if a < b else a


def cmin(a: float, b: float) -> float:
    """std::min: `a` unless b < a."""
    return b if b < a else a


def cclamp(value: float, lower: float, upper: float) -> float:
    """std::clamp: a NaN value or bound passes the value through."""
    if value < lower:
        return lower
    if upper < value:
        return upper
    return value


def is_limited(value: float, lower: float, upper: float) -> bool:
    return value < lower or value > upper


def _ordered(lower: float, upper: float) -> tuple[float, float]:
    return (upper, lower) if lower > upper else (lower, upper)


class JointPositionOutOfBounds(RuntimeError):
    """A position command while the joint is measured well outside its position limits."""


def check_actual_position(joint_name: str, actual_position: float | None, limits: JointLimits) -> None:
    """Raise when a measured position is past its limits by more than the fault tolerance: commanding a position
    from there could drive the joint into its hard stop."""
    if actual_position is None or not limits.has_position_limits:
        return
    if (
        actual_position > limits.max_position + OUT_OF_BOUNDS_EXCEPTION_TOLERANCE
        or actual_position < limits.min_position - OUT_OF_BOUNDS_EXCEPTION_TOLERANCE
    ):
        raise JointPositionOutOfBounds(
            f"Joint position is out of bounds for the joint : '{joint_name}' actual position: "
            f"{actual_position} limits: [{limits.min_position}, {limits.max_position}]. This could be due to a "
            f"hardware failure (or) the physical limits of the joint being larger than the ones defined in the URDF. "
            f"Please recheck the URDF and the hardware to verify the joint limits."
        )


def compute_position_limits(
    joint_name: str,
    limits: JointLimits,
    actual_velocity: float | None,
    actual_position: float | None,
    previous_command_position: float | None,
    dt_s: float,
) -> tuple[float, float]:
    """The position range: the position limits, and with a velocity limit no farther than one period's travel
    at that speed (or what acceleration allows from the measured speed) from the previous command, else from the
    measured position."""
    lower, upper = limits.min_position, limits.max_position
    check_actual_position(joint_name, actual_position, limits)
    if limits.has_velocity_limits:
        speed = abs(actual_velocity) if actual_velocity is not None else 0.0
        reachable = speed + limits.max_acceleration * dt_s if limits.has_acceleration_limits else limits.max_velocity
        step = cmin(limits.max_velocity, reachable) * dt_s
        # The previous command, not the measurement: the state lags the command by a cycle or two, and stepping
        # from it would keep the joint well under its speed limit.
        ref = previous_command_position if previous_command_position is not None else actual_position
        if ref is not None:
            lower = cmax(cmin(ref - step, upper), lower)
            upper = cmin(cmax(ref + step, lower), upper)
    return _ordered(lower, upper)


def compute_velocity_limits(
    joint_name: str,
    limits: JointLimits,
    desired_velocity: float,
    actual_position: float | None,
    previous_command_velocity: float | None,
    dt_s: float,
) -> tuple[float, float]:
    """The velocity range: ±max_velocity, no faster than reaches a position limit within the period, zero when
    the joint is past a limit (or, within the tolerance, when asked to go further out), and within one period's
    acceleration of the previous command."""
    del joint_name  # named in upstream's warnings only
    if not limits.has_velocity_limits:
        return -_INF, _INF
    lower, upper = -limits.max_velocity, limits.max_velocity
    if limits.has_position_limits and actual_position is not None:
        pos = actual_position
        lower = cmax((limits.min_position - pos) / dt_s, lower)
        upper = cmin((limits.max_position - pos) / dt_s, upper)
        if pos > limits.max_position or pos < limits.min_position:
            tol = POSITION_BOUNDS_TOLERANCE
            barely_over = pos < limits.max_position + tol and pos > limits.min_position and desired_velocity >= 0.0
            barely_under = pos > limits.min_position - tol and pos < limits.max_position and desired_velocity <= 0.0
            far_out = pos > limits.max_position + tol or pos < limits.min_position - tol
            if barely_over or barely_under or far_out:
                lower = upper = 0.0
    if limits.has_acceleration_limits and previous_command_velocity is not None:
        dv = limits.max_acceleration * dt_s
        lower = cmax(previous_command_velocity - dv, lower)
        upper = cmin(previous_command_velocity + dv, upper)
    return _ordered(lower, upper)


def compute_effort_limits(
    limits: JointLimits, actual_position: float | None, actual_velocity: float | None, dt_s: float
) -> tuple[float, float]:
    """The effort range: ±max_effort, with no effort pushing further out at a position limit or past the
    velocity limit."""
    del dt_s
    if not limits.has_effort_limits:
        return -_INF, _INF
    lower, upper = -limits.max_effort, limits.max_effort
    if limits.has_position_limits and actual_position is not None and actual_velocity is not None:
        if actual_position <= limits.min_position and actual_velocity <= 0.0:
            lower = 0.0
        elif actual_position >= limits.max_position and actual_velocity >= 0.0:
            upper = 0.0
    if limits.has_velocity_limits and actual_velocity is not None:
        if actual_velocity < -limits.max_velocity:
            lower = 0.0
        elif actual_velocity > limits.max_velocity:
            upper = 0.0
    return _ordered(lower, upper)


def compute_acceleration_limits(
    limits: JointLimits, desired_acceleration: float, actual_velocity: float | None
) -> tuple[float, float]:
    """±max_deceleration when the acceleration asked for slows the joint down (it opposes the measured
    velocity), else ±max_acceleration; unbounded without the matching limit."""
    slowing = actual_velocity is not None and (
        (desired_acceleration < 0 and actual_velocity > 0) or (desired_acceleration > 0 and actual_velocity < 0)
    )
    if limits.has_deceleration_limits and slowing:
        return _ordered(-limits.max_deceleration, limits.max_deceleration)
    if limits.has_acceleration_limits:
        return _ordered(-limits.max_acceleration, limits.max_acceleration)
    return -_INF, _INF
