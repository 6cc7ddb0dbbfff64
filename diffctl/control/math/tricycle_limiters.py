"""tricycle_controller's limiters (Jazzy): magnitude bounds, the same in both directions.

TractionLimiter bounds the wheel speed's magnitude to [min_velocity, max_velocity], its change per second to
[min_acceleration, max_acceleration] while speeding up (|v| ≥ |v0|) or [min_deceleration, max_deceleration] while
slowing down, and the change of that change to [min_jerk, max_jerk] (the jerk step is 2·dt², as upstream).
SteeringLimiter bounds the angle to [min_position, max_position], its rate to [min_velocity, max_velocity] and its
second difference to [min_acceleration, max_acceleration]. A bound given alone gets its partner (a maximum 1000,
a minimum 0; a position limit mirrored); NaN switches a pair off. Negative or crossed bounds are refused
(`ValueError`, upstream's texts). `limit(v, v0, v1, dt)` returns the limited value and the factor it was scaled by.
Note that a minimum above zero forces at least that much change, as upstream does.
"""

from __future__ import annotations

import math

_BIG = 1000.0
_BOTH_WAYS = (" The positive limit will be applied to both directions. Setting different limits for positive and "
              "negative directions is not supported. Actuators are assumed to have the same constraints in both "
              "directions")


def _pair(lo: float, hi: float) -> tuple[float, float]:
    if not math.isnan(lo) and math.isnan(hi):
        hi = _BIG
    if not math.isnan(hi) and math.isnan(lo):
        lo = 0.0
    return lo, hi


def _on(pair: tuple[float, float]) -> bool:
    return not (math.isnan(pair[0]) or math.isnan(pair[1]))


def _bounded_step(step: float, lo: float, hi: float) -> float:
    """`step` with its magnitude clamped to [lo, hi], keeping its sign (0 counts as positive)."""
    size = min(max(abs(step), lo), hi)
    return size if step >= 0 else -size


def _factor(before: float, after: float) -> float:
    return after / before if before != 0.0 else 1.0


class TractionLimiter:
    def __init__(self, min_velocity: float = math.nan, max_velocity: float = math.nan,
                 min_acceleration: float = math.nan, max_acceleration: float = math.nan,
                 min_deceleration: float = math.nan, max_deceleration: float = math.nan,
                 min_jerk: float = math.nan, max_jerk: float = math.nan) -> None:
        self.velocity = _pair(min_velocity, max_velocity)
        self.acceleration = _pair(min_acceleration, max_acceleration)
        self.deceleration = _pair(min_deceleration, max_deceleration)
        self.jerk = _pair(min_jerk, max_jerk)
        for name, (lo, hi), noun in (("velocity", self.velocity, "Velocity cannot be negative."),
                                     ("acceleration", self.acceleration, "Acceleration limits cannot be negative."),
                                     ("deceleration", self.deceleration, "Deceleration limits cannot be negative."),
                                     ("jerk", self.jerk, "Jerk limits cannot be negative.")):
            if lo < 0 or hi < 0:
                raise ValueError(noun + _BOTH_WAYS)
            if lo > hi:
                raise ValueError(f"Min {name} cannot be greater than max {name}.")

    def limit(self, v: float, v0: float, v1: float, dt_s: float) -> tuple[float, float]:
        before = v
        if _on(self.jerk):
            v = self.limit_jerk(v, v0, v1, dt_s)[0]
        if _on(self.acceleration):
            v = self.limit_acceleration(v, v0, dt_s)[0]
        if _on(self.velocity):
            v = self.limit_velocity(v)[0]
        return v, _factor(before, v)

    def limit_velocity(self, v: float) -> tuple[float, float]:
        lo, hi = self.velocity
        out = min(max(abs(v), lo), hi) * (1.0 if v >= 0 else -1.0)
        return out, _factor(v, out)

    def limit_acceleration(self, v: float, v0: float, dt_s: float) -> tuple[float, float]:
        lo, hi = self.acceleration if abs(v) >= abs(v0) else self.deceleration
        out = v0 + _bounded_step(v - v0, lo * dt_s, hi * dt_s)
        return out, _factor(v, out)

    def limit_jerk(self, v: float, v0: float, v1: float, dt_s: float) -> tuple[float, float]:
        lo, hi = self.jerk
        twice_dt2 = 2.0 * dt_s * dt_s
        previous_step = v0 - v1
        out = v0 + previous_step + _bounded_step((v - v0) - previous_step, lo * twice_dt2, hi * twice_dt2)
        return out, _factor(v, out)


class SteeringLimiter:
    def __init__(self, min_position: float = math.nan, max_position: float = math.nan,
                 min_velocity: float = math.nan, max_velocity: float = math.nan,
                 min_acceleration: float = math.nan, max_acceleration: float = math.nan) -> None:
        if not math.isnan(min_position) and math.isnan(max_position):
            max_position = -min_position
        if not math.isnan(max_position) and math.isnan(min_position):
            min_position = -max_position
        self.position = (min_position, max_position)
        self.velocity = _pair(min_velocity, max_velocity)
        self.acceleration = _pair(min_acceleration, max_acceleration)
        if self.velocity[0] < 0 or self.velocity[1] < 0:
            raise ValueError("Velocity cannot be negative." + _BOTH_WAYS[1:])
        if self.acceleration[0] < 0 or self.acceleration[1] < 0:
            raise ValueError("Acceleration cannot be negative." + _BOTH_WAYS[1:])

    def limit(self, p: float, p0: float, p1: float, dt_s: float) -> tuple[float, float]:
        before = p
        if _on(self.acceleration):
            lo, hi = self.acceleration
            twice_dt2 = 2.0 * dt_s * dt_s
            previous_step = p0 - p1
            p = p0 + previous_step + _bounded_step((p - p0) - previous_step, lo * twice_dt2, hi * twice_dt2)
        if _on(self.velocity):
            lo, hi = self.velocity
            p = p0 + _bounded_step(p - p0, lo * dt_s, hi * dt_s)
        if _on(self.position):
            p = min(max(p, self.position[0]), self.position[1])
        return p, _factor(before, p)
