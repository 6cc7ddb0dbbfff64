"""Pure math of Gazebo's DiffDrive system: speed limiting, wheel speeds, odometry from wheel angles.

Follows gz-sim's SpeedLimiter (jerk, then acceleration, then velocity clamp) and gz-math's
DiffDriveOdometry (exact arc integration, velocities as a rolling mean over the last samples).
"""

from __future__ import annotations

import collections
import math
from dataclasses import dataclass


@dataclass(frozen=True)
class Limits:
    """Bounds on one speed (linear m/s or angular rad/s) and its derivatives; None = unbounded."""

    min_velocity: float | None = None
    max_velocity: float | None = None
    min_acceleration: float | None = None
    max_acceleration: float | None = None
    min_jerk: float | None = None
    max_jerk: float | None = None

    @property
    def rate_limited(self) -> bool:
        return any(v is not None for v in (self.min_acceleration, self.max_acceleration, self.min_jerk, self.max_jerk))


def _clamp(x: float, lo: float | None, hi: float | None) -> float:
    if lo is not None and x < lo:
        x = lo
    if hi is not None and x > hi:
        x = hi
    return x


def limit_speed(target: float, v0: float, v1: float, dt_s: float, lim: Limits) -> float:
    """The speed to command now, given the target, the last two commanded speeds (v0 newest) and `dt_s`."""
    v = target
    if dt_s > 0:
        if lim.min_jerk is not None or lim.max_jerk is not None:
            dv, dv0 = v - v0, v0 - v1
            dt2 = 2.0 * dt_s * dt_s
            lo = lim.min_jerk * dt2 if lim.min_jerk is not None else None
            hi = lim.max_jerk * dt2 if lim.max_jerk is not None else None
            v = v0 + dv0 + _clamp(dv - dv0, lo, hi)
        if lim.min_acceleration is not None or lim.max_acceleration is not None:
            lo = lim.min_acceleration * dt_s if lim.min_acceleration is not None else None
            hi = lim.max_acceleration * dt_s if lim.max_acceleration is not None else None
            v = v0 + _clamp(v - v0, lo, hi)
    return _clamp(v, lim.min_velocity, lim.max_velocity)


def wheel_speeds_rad_s(
    linear_m_s: float, angular_rad_s: float, wheel_separation_m: float, wheel_radius_m: float
) -> tuple[float, float]:
    """(left, right) wheel angular speeds for a body twist."""
    half = angular_rad_s * wheel_separation_m / 2.0
    return (linear_m_s - half) / wheel_radius_m, (linear_m_s + half) / wheel_radius_m


class Odometry:
    """Pose (x, y, heading) and velocities integrated from left/right wheel angles."""

    def __init__(self, wheel_separation_m: float, wheel_radius_m: float, window: int = 10) -> None:
        self.separation = wheel_separation_m
        self.radius = wheel_radius_m
        self.window = window
        self.reset()

    def reset(self) -> None:
        self.x_m = 0.0
        self.y_m = 0.0
        self.heading_rad = 0.0
        self.linear_m_s = 0.0
        self.angular_rad_s = 0.0
        self._last: tuple[float, float, float] | None = None
        self._lin: collections.deque[float] = collections.deque(maxlen=self.window)
        self._ang: collections.deque[float] = collections.deque(maxlen=self.window)

    def update(self, left_rad: float, right_rad: float, time_s: float) -> None:
        if self._last is None:
            self._last = (left_rad, right_rad, time_s)
            return
        l0, r0, t0 = self._last
        dt = time_s - t0
        if dt <= 0:
            return
        self._last = (left_rad, right_rad, time_s)
        dl = (left_rad - l0) * self.radius
        dr = (right_rad - r0) * self.radius
        linear = (dl + dr) / 2.0
        angular = (dr - dl) / self.separation
        self.integrate(linear, angular)
        self._lin.append(linear / dt)
        self._ang.append(angular / dt)
        self.linear_m_s = sum(self._lin) / len(self._lin)
        self.angular_rad_s = sum(self._ang) / len(self._ang)

    def integrate(self, linear_m: float, angular_rad: float) -> None:
        if abs(angular_rad) < 1e-6:
            # Second-order Runge-Kutta for (nearly) straight motion.
            direction = self.heading_rad + angular_rad * 0.5
            self.x_m += linear_m * math.cos(direction)
            self.y_m += linear_m * math.sin(direction)
            self.heading_rad += angular_rad
        else:
            # Exact arc.
            h0 = self.heading_rad
            r = linear_m / angular_rad
            self.heading_rad += angular_rad
            self.x_m += r * (math.sin(self.heading_rad) - math.sin(h0))
            self.y_m += -r * (math.cos(self.heading_rad) - math.cos(h0))
