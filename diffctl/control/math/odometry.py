"""Planar odometry of a differential drive (diff_drive_controller's Odometry, Jazzy tip).

Pose integration is exact along the arc when the heading changes, and second-order Runge-Kutta when the
angular step is below 1e-6 rad (where the arc radius blows up). The reported twist is the rolling mean of
the last `velocity_rolling_window_size` per-update velocities. Updates closer than 0.1 ms to the previous one
are skipped, as in the reference.

One deliberate difference from the reference: the reference starts its clock at t = 0 and its wheel
positions at 0, so the first update after start-up integrates over "time since epoch" or jumps by the
initial wheel angle. Here `init(time_s, left_wheel_pos_rad, right_wheel_pos_rad)` sets both, and the
controller calls it on its first update.
"""

from __future__ import annotations

import math

from diffctl.control.math.rolling_mean import RollingMean

_MIN_DT_S = 0.0001  # the reference's "too close to the previous update" threshold
_RK2_BELOW_RAD = 1e-6
_sin, _cos = math.sin, math.cos


class Odometry:
    """Pose (x_m, y_m, heading_rad) and rolling-mean twist (linear_mps, angular_radps) of the base."""

    __slots__ = (
        "_angular_mean",
        "_left_wheel_old_pos_m",
        "_linear_mean",
        "_right_wheel_old_pos_m",
        "angular_radps",
        "heading_rad",
        "left_wheel_radius_m",
        "linear_mps",
        "right_wheel_radius_m",
        "timestamp_s",
        "wheel_separation_m",
        "x_m",
        "y_m",
    )

    def __init__(
        self,
        wheel_separation_m: float,
        left_wheel_radius_m: float,
        right_wheel_radius_m: float,
        velocity_rolling_window_size: int = 10,
    ) -> None:
        self.wheel_separation_m = wheel_separation_m
        self.left_wheel_radius_m = left_wheel_radius_m
        self.right_wheel_radius_m = right_wheel_radius_m
        self._linear_mean = RollingMean(velocity_rolling_window_size)
        self._angular_mean = RollingMean(velocity_rolling_window_size)
        self.timestamp_s = 0.0
        self._left_wheel_old_pos_m = 0.0
        self._right_wheel_old_pos_m = 0.0
        self.x_m = 0.0
        self.y_m = 0.0
        self.heading_rad = 0.0
        self.linear_mps = 0.0
        self.angular_radps = 0.0

    # --- start / reset --------------------------------------------------------------------------------------
    def init(self, time_s: float, left_wheel_pos_rad: float = 0.0, right_wheel_pos_rad: float = 0.0) -> None:
        """Start counting from `time_s` and these wheel angles; clears the twist averages, keeps the pose."""
        self.timestamp_s = time_s
        self._left_wheel_old_pos_m = left_wheel_pos_rad * self.left_wheel_radius_m
        self._right_wheel_old_pos_m = right_wheel_pos_rad * self.right_wheel_radius_m
        self._linear_mean.reset()
        self._angular_mean.reset()
        self.linear_mps = 0.0
        self.angular_radps = 0.0

    def reset_pose(self) -> None:
        """The reference's resetOdometry(): zero x, y and heading (twist and clock are kept)."""
        self.x_m = 0.0
        self.y_m = 0.0
        self.heading_rad = 0.0

    # --- updates --------------------------------------------------------------------------------------------
    def update_from_position(self, left_wheel_pos_rad: float, right_wheel_pos_rad: float, time_s: float) -> bool:
        """Integrate from absolute wheel angles (position feedback). False if too soon after the last update."""
        if time_s - self.timestamp_s < _MIN_DT_S:
            return False
        left_pos_m = left_wheel_pos_rad * self.left_wheel_radius_m
        right_pos_m = right_wheel_pos_rad * self.right_wheel_radius_m
        left_step_m = left_pos_m - self._left_wheel_old_pos_m
        right_step_m = right_pos_m - self._right_wheel_old_pos_m
        self._left_wheel_old_pos_m = left_pos_m
        self._right_wheel_old_pos_m = right_pos_m
        return self.update_from_step(left_step_m, right_step_m, time_s)

    def update_from_step(self, left_step_m: float, right_step_m: float, time_s: float) -> bool:
        """Integrate the distance each wheel rolled since the last update (the reference's updateFromVelocity,
        which velocity feedback feeds with wheel_velocity * radius * period)."""
        dt_s = time_s - self.timestamp_s
        if dt_s < _MIN_DT_S:
            return False
        linear_m = (left_step_m + right_step_m) * 0.5
        angular_rad = (right_step_m - left_step_m) / self.wheel_separation_m
        self.integrate_exact(linear_m, angular_rad)
        self.timestamp_s = time_s
        self._linear_mean.accumulate(linear_m / dt_s)
        self._angular_mean.accumulate(angular_rad / dt_s)
        self.linear_mps = self._linear_mean.mean
        self.angular_radps = self._angular_mean.mean
        return True

    def update_open_loop(self, linear_mps: float, angular_radps: float, time_s: float) -> None:
        """Integrate the commanded body twist over the time since the last update (no feedback)."""
        self.linear_mps = linear_mps
        self.angular_radps = angular_radps
        dt_s = time_s - self.timestamp_s
        self.timestamp_s = time_s
        self.integrate_exact(linear_mps * dt_s, angular_radps * dt_s)

    # --- integration ----------------------------------------------------------------------------------------
    def integrate_exact(self, linear_m: float, angular_rad: float) -> None:
        """Move along the arc of length `linear_m` that turns the heading by `angular_rad`."""
        if -_RK2_BELOW_RAD < angular_rad < _RK2_BELOW_RAD:
            # integrate_runge_kutta2, written out (every control cycle of a car driving straight)
            direction = self.heading_rad + angular_rad * 0.5
            self.x_m += linear_m * _cos(direction)
            self.y_m += linear_m * _sin(direction)
            self.heading_rad += angular_rad
            return
        heading_old = self.heading_rad
        radius_m = linear_m / angular_rad
        self.heading_rad += angular_rad
        self.x_m += radius_m * (_sin(self.heading_rad) - _sin(heading_old))
        self.y_m += -radius_m * (_cos(self.heading_rad) - _cos(heading_old))

    def integrate_runge_kutta2(self, linear_m: float, angular_rad: float) -> None:
        direction = self.heading_rad + angular_rad * 0.5
        self.x_m += linear_m * math.cos(direction)
        self.y_m += linear_m * math.sin(direction)
        self.heading_rad += angular_rad
