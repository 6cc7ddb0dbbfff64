"""Pure math of Gazebo's MecanumDrive and AckermannSteering systems (gz-sim 8, gz-math 7).

Mecanum: wheel speeds from a body twist with the half sum of separation and wheelbase as the lever arm, and
gz-math's MecanumDriveOdometry (wheel travel → body linear/lateral/angular, exact arc integration, velocities as
a rolling mean). Ackermann: the turning radius from v/ω bounded by the steering limit, the two steering angles
about a kingpin half-width either side, wheel speeds of a simple differential, and the system's own dead
reckoning from the mean steering angle and the driven wheels' travel.
"""

from __future__ import annotations

import collections
import math

# AckermannSteering: an |ω| below this drives straight; a radius this large stands for straight.
MIN_TURN_RATE_RAD_S = 0.001
STRAIGHT_RADIUS_M = 1e9


def mecanum_wheel_speeds(
    linear_m_s: float,
    lateral_m_s: float,
    angular_rad_s: float,
    separation_m: float,
    wheelbase_m: float,
    radius_m: float,
) -> tuple[float, float, float, float]:
    """(front left, front right, back left, back right) wheel speeds in rad/s."""
    arm = 0.5 * (separation_m + wheelbase_m)
    turn = angular_rad_s * arm
    return (
        (linear_m_s - lateral_m_s - turn) / radius_m,
        (linear_m_s + lateral_m_s + turn) / radius_m,
        (linear_m_s + lateral_m_s - turn) / radius_m,
        (linear_m_s - lateral_m_s + turn) / radius_m,
    )


class MecanumOdometry:
    """Pose (x, y, heading) and velocities from the four wheel angles (gz-math MecanumDriveOdometry)."""

    def __init__(self, separation_m: float, wheelbase_m: float, radius_m: float, window: int = 10) -> None:
        self.separation = separation_m
        self.wheelbase = wheelbase_m
        self.radius = radius_m
        self.window = window
        self.initialized = False
        self.reset(0.0)
        self.initialized = False

    def reset(self, time_s: float) -> None:
        """gz-math's Init: zero pose, zero wheel travel remembered (the next update sees the whole angle)."""
        self.x_m = self.y_m = self.heading_rad = 0.0
        self.linear_m_s = self.lateral_m_s = self.angular_rad_s = 0.0
        self._old = (0.0, 0.0, 0.0, 0.0)
        self._last_time_s = time_s
        self._means = [collections.deque(maxlen=self.window) for _ in range(3)]
        self.initialized = True

    def update(self, fl_rad: float, fr_rad: float, bl_rad: float, br_rad: float, time_s: float) -> None:
        dt = time_s - self._last_time_s
        now = (fl_rad * self.radius, fr_rad * self.radius, bl_rad * self.radius, br_rad * self.radius)
        fl, fr, bl, br = (n - o for n, o in zip(now, self._old, strict=True))
        self._old = now
        linear = (fl + fr + bl + br) * 0.25
        lateral = (-fl + fr + bl - br) * 0.25
        angular = (-fl + fr - bl + br) / (4 * 0.5 * (self.separation + self.wheelbase))
        self._integrate(linear, lateral, angular)
        if abs(dt) < 1e-6:  # gz-math compares with its default tolerance
            return
        self._last_time_s = time_s
        for mean, value in zip(self._means, (linear, lateral, angular), strict=True):
            mean.append(value / dt)
        self.linear_m_s, self.lateral_m_s, self.angular_rad_s = (sum(m) / len(m) for m in self._means)

    def _integrate(self, linear: float, lateral: float, angular: float) -> None:
        h0 = self.heading_rad
        if abs(angular) < 1e-6:
            direction = h0 + angular * 0.5
            self.x_m += linear * math.cos(direction) - lateral * math.sin(direction)
            self.y_m += linear * math.sin(direction) + lateral * math.cos(direction)
            self.heading_rad += angular
            return
        r, r2 = linear / angular, lateral / angular
        self.heading_rad += angular
        h1 = self.heading_rad
        self.x_m += r * (math.sin(h1) - math.sin(h0)) + r2 * (math.cos(h1) - math.cos(h0))
        self.y_m += -r * (math.cos(h1) - math.cos(h0)) + r2 * (math.sin(h1) - math.sin(h0))


def ackermann_command(
    linear_m_s: float,
    angular_rad_s: float,
    wheel_base_m: float,
    wheel_separation_m: float,
    kingpin_width_m: float,
    steering_limit_rad: float,
    wheel_radius_m: float,
) -> tuple[float, float, float, float]:
    """(left steering angle, right steering angle, left wheel speed, right wheel speed) for a body twist."""
    radius = linear_m_s / angular_rad_s if angular_rad_s != 0.0 else math.copysign(math.inf, linear_m_s or 1.0)
    minimum = wheel_base_m / math.sin(steering_limit_rad)
    if abs(linear_m_s) > 0.0:
        if 0.0 <= radius < minimum:
            radius = minimum
        if -minimum < radius <= 0.0:
            radius = -minimum
    elif abs(angular_rad_s) >= MIN_TURN_RATE_RAD_S:
        radius = math.copysign(minimum, angular_rad_s)
    if abs(angular_rad_s) < MIN_TURN_RATE_RAD_S:
        radius = STRAIGHT_RADIUS_M
    left = math.atan(wheel_base_m / (radius - kingpin_width_m / 2.0))
    right = math.atan(wheel_base_m / (radius + kingpin_width_m / 2.0))
    tan_phi = wheel_base_m / radius
    spread = wheel_separation_m * tan_phi / (2.0 * wheel_base_m)
    return left, right, linear_m_s * (1.0 - spread) / wheel_radius_m, linear_m_s * (1.0 + spread) / wheel_radius_m


def ackermann_steer_only(angle_rad: float, wheel_base_m: float, wheel_separation_m: float) -> tuple[float, float]:
    """(left, right) steering angles for a commanded mean steering angle (AckermannSteering's steering_only)."""
    s, c = math.sin(angle_rad), math.cos(angle_rad)
    left = math.atan(2.0 * wheel_base_m * s / (2.0 * wheel_base_m * c - wheel_separation_m * s))
    right = math.atan(2.0 * wheel_base_m * s / (2.0 * wheel_base_m * c + wheel_separation_m * s))
    return left, right


class AckermannOdometry:
    """AckermannSteering's own dead reckoning: yaw from the mean steering angle, then the position step along
    the new yaw; velocities are those of the last update (no averaging)."""

    def __init__(self, wheel_base_m: float, wheel_radius_m: float) -> None:
        self.wheel_base = wheel_base_m
        self.radius = wheel_radius_m
        self.reset()

    def reset(self) -> None:
        self.x_m = self.y_m = self.heading_rad = 0.0
        self.linear_m_s = self.angular_rad_s = 0.0
        self._old = (0.0, 0.0)
        self._last_time_s = 0.0

    def update(self, left_rad: float, right_rad: float, left_steer: float, right_steer: float, time_s: float) -> None:
        phi = 0.5 * (left_steer + right_steer)
        tan_phi = math.tan(phi)
        dist = 0.5 * self.radius * ((left_rad - self._old[0]) + (right_rad - self._old[1]))
        delta = dist * tan_phi / self.wheel_base  # dist / (wheel_base / tan(phi)), finite when phi is 0
        self.heading_rad = math.remainder(self.heading_rad + delta, 2 * math.pi)
        self.x_m += dist * math.cos(self.heading_rad)
        self.y_m += dist * math.sin(self.heading_rad)
        dt = time_s - self._last_time_s
        if dt > 0:
            self.linear_m_s, self.angular_rad_s = dist / dt, delta / dt
        self._last_time_s = time_s
        self._old = (left_rad, right_rad)
