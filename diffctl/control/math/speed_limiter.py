"""Velocity, acceleration and jerk limiter of diff_drive_controller (Jazzy tip: control_toolbox RateLimiter).

Limits are given in diff_drive_controller's names (`SpeedLimits`) and resolved once, as the reference does:
  - a NaN `max_*` switches that group off (velocity: max_velocity, acceleration: max_acceleration,
    jerk: max_jerk);
  - a NaN `min_velocity` / `min_jerk` / `max_acceleration_reverse` defaults to minus its maximum;
  - a NaN `max_deceleration` defaults to `max_acceleration_reverse` and a NaN `max_deceleration_reverse`
    to `max_acceleration` (symmetric limits);
  - a minimum above its maximum is an error (`LimitError`, naming the offending parameter).
Signs: `max_acceleration`, `max_deceleration_reverse`, `max_jerk` ≥ 0 bound a change from above;
`max_acceleration_reverse`, `max_deceleration`, `min_jerk` ≤ 0 bound it from below.

`limit(v, v0, v1, dt)` applies jerk, then acceleration, then velocity, where v0 and v1 are the last two
limited commands. The jerk limit only acts while the change grows (control_toolbox#240). Which
acceleration bounds apply depends on the sign of v0: forward (v0 > 0) uses [max_deceleration,
max_acceleration], reverse (v0 < 0) [max_acceleration_reverse, max_deceleration_reverse], standstill
[max_acceleration_reverse, max_acceleration].
"""

from __future__ import annotations

import math
from dataclasses import dataclass

_NAN = math.nan


class LimitError(ValueError):
    """Limits that contradict each other; `field` names the parameter to fix (e.g. "min_velocity")."""

    def __init__(self, field: str, message: str) -> None:
        super().__init__(message)
        self.field = field
        self.message = message


@dataclass(frozen=True)
class SpeedLimits:
    """One axis' limits in diff_drive_controller's parameter names; NaN = unset."""

    min_velocity: float = _NAN
    max_velocity: float = _NAN
    max_acceleration_reverse: float = _NAN
    max_acceleration: float = _NAN
    max_deceleration: float = _NAN
    max_deceleration_reverse: float = _NAN
    min_jerk: float = _NAN
    max_jerk: float = _NAN


def _clamp(v: float, lo: float, hi: float) -> float:
    # std::clamp ordering: a NaN v passes through unchanged.
    if v < lo:
        return lo
    if hi < v:
        return hi
    return v


class SpeedLimiter:
    """Resolved limits of one axis; `limit()` is pure (the caller keeps the command history)."""

    __slots__ = (
        "has_acceleration_limits",
        "has_jerk_limits",
        "has_velocity_limits",
        "limits",
        "max_accel_neg",
        "max_accel_pos",
        "max_jerk",
        "max_velocity",
        "min_accel_neg",
        "min_accel_pos",
        "min_jerk",
        "min_velocity",
    )

    def __init__(self, limits: SpeedLimits | None = None) -> None:
        lim = limits or SpeedLimits()
        self.limits = lim
        isnan = math.isnan

        self.has_velocity_limits = not isnan(lim.max_velocity)
        self.max_velocity = lim.max_velocity
        self.min_velocity = -lim.max_velocity if isnan(lim.min_velocity) else lim.min_velocity
        if self.has_velocity_limits and self.min_velocity > self.max_velocity:
            raise LimitError(
                "min_velocity",
                f"min_velocity {self.min_velocity!r} is above max_velocity {self.max_velocity!r}",
            )

        # Names of control_toolbox: *_neg apply while moving in reverse, *_pos while moving forward.
        self.has_acceleration_limits = not isnan(lim.max_acceleration)
        self.max_accel_pos = lim.max_acceleration
        self.min_accel_neg = (
            -lim.max_acceleration if isnan(lim.max_acceleration_reverse) else lim.max_acceleration_reverse
        )
        self.max_accel_neg = lim.max_deceleration_reverse
        self.min_accel_pos = lim.max_deceleration
        if self.has_acceleration_limits:
            if self.min_accel_neg > self.max_accel_pos:
                raise LimitError(
                    "max_acceleration_reverse",
                    f"max_acceleration_reverse {self.min_accel_neg!r} is above max_acceleration "
                    f"{self.max_accel_pos!r} (it bounds reverse acceleration from below: give a value ≤ 0)",
                )
            if isnan(self.max_accel_neg):
                self.max_accel_neg = self.max_accel_pos
            if isnan(self.min_accel_pos):
                self.min_accel_pos = self.min_accel_neg
            if self.min_accel_pos > self.max_accel_neg:
                raise LimitError(
                    "max_deceleration",
                    f"max_deceleration {self.min_accel_pos!r} is above max_deceleration_reverse "
                    f"{self.max_accel_neg!r} (max_deceleration bounds forward braking from below: give a value ≤ 0)",
                )

        self.has_jerk_limits = not isnan(lim.max_jerk)
        self.max_jerk = lim.max_jerk
        self.min_jerk = -lim.max_jerk if isnan(lim.min_jerk) else lim.min_jerk
        if self.has_jerk_limits and self.min_jerk > self.max_jerk:
            raise LimitError("min_jerk", f"min_jerk {self.min_jerk!r} is above max_jerk {self.max_jerk!r}")

    @property
    def enabled(self) -> bool:
        return self.has_velocity_limits or self.has_acceleration_limits or self.has_jerk_limits

    def limit(self, v: float, v0: float, v1: float, dt: float) -> float:
        """`v` limited in jerk, acceleration and velocity, given the last two limited commands v0, v1."""
        # limit_acceleration and the velocity clamp written out: this runs twice in every control cycle.
        if self.has_jerk_limits:
            v = self.limit_jerk(v, v0, v1, dt)
        if self.has_acceleration_limits:
            if v0 > 0.0:
                lo, hi = self.min_accel_pos, self.max_accel_pos
            elif v0 < 0.0:
                lo, hi = self.min_accel_neg, self.max_accel_neg
            else:
                lo, hi = self.min_accel_neg, self.max_accel_pos
            dv = v - v0
            lo *= dt
            hi *= dt
            v = v0 + (lo if dv < lo else hi if hi < dv else dv)  # _clamp(dv, lo, hi)
        if self.has_velocity_limits:
            lo, hi = self.min_velocity, self.max_velocity
            v = lo if v < lo else hi if hi < v else v  # _clamp(v, lo, hi)
        return v

    def limit_velocity(self, v: float) -> float:
        return _clamp(v, self.min_velocity, self.max_velocity) if self.has_velocity_limits else v

    def limit_acceleration(self, v: float, v0: float, dt: float) -> float:
        if not self.has_acceleration_limits:
            return v
        if v0 > 0.0:
            lo, hi = self.min_accel_pos, self.max_accel_pos
        elif v0 < 0.0:
            lo, hi = self.min_accel_neg, self.max_accel_neg
        else:
            lo, hi = self.min_accel_neg, self.max_accel_pos
        return v0 + _clamp(v - v0, lo * dt, hi * dt)

    def limit_jerk(self, v: float, v0: float, v1: float, dt: float) -> float:
        if not self.has_jerk_limits:
            return v
        dv = v - v0
        dv0 = v0 - v1
        # Only while the acceleration grows in the direction of motion change; limiting the jerk while it
        # shrinks makes closed loops oscillate (control_toolbox#240).
        if (dv - dv0) * dv > 0.0:
            dt2 = dt * dt
            return v0 + dv0 + _clamp(dv - dv0, self.min_jerk * dt2, self.max_jerk * dt2)
        return v
