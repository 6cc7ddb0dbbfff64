"""tricycle_controller's kinematics (Jazzy): one steered, driven wheel at `wheelbase_m` ahead of the rear axle.

Forward: the wheel's rim speed Vs = ω·r splits into the base's forward speed Vs·cos α and its turn rate
Vs·sin α / wheelbase; the pose integrates along arcs (planar_pose) and the reported twist is the rolling mean of
the last `window` samples. Inverse (`wheel_command`): a twist (v, ω) needs the steering angle atan(ω·L / v) and
the wheel speed v / (r·cos α); turning on the spot (v = 0) points the wheel sideways (±π/2) at |ω|·L / r.
"""

from __future__ import annotations

import math

from diffctl.control.math.planar_pose import PlanarPose
from diffctl.control.math.rolling_mean import RollingMean


def wheel_command(linear_mps: float, angular_radps: float, wheelbase_m: float, wheel_radius_m: float
                  ) -> tuple[float, float]:
    """(steering angle rad, wheel speed rad/s) for a body twist."""
    if linear_mps == 0 and angular_radps != 0:
        return (math.pi / 2 if angular_radps > 0 else -math.pi / 2), abs(angular_radps) * wheelbase_m / wheel_radius_m
    alpha = 0.0 if angular_radps == 0 or linear_mps == 0 else math.atan(angular_radps * wheelbase_m / linear_mps)
    return alpha, linear_mps / (wheel_radius_m * math.cos(alpha))


def turn_in_scale(angle_error_rad: float) -> float:
    """How much of the wheel speed to give while the steering is still `angle_error_rad` away from its target: all
    of it under 30°, cos(error) up to 90°, 1 % beyond."""
    if angle_error_rad < math.pi / 6:
        return 1.0
    if angle_error_rad > math.pi / 2:
        return 0.01
    return math.cos(angle_error_rad)


class TricycleOdometry:
    def __init__(self, wheelbase_m: float = 0.0, wheel_radius_m: float = 0.0, window: int = 10) -> None:
        self.wheelbase_m = wheelbase_m
        self.wheel_radius_m = wheel_radius_m
        self.pose = PlanarPose()
        self._linear = RollingMean(window)
        self._angular = RollingMean(window)
        self.linear_mps = self.angular_radps = 0.0

    def set_window(self, window: int) -> None:
        self._linear, self._angular = RollingMean(window), RollingMean(window)

    def reset(self) -> None:
        self.pose.reset()
        self._linear.reset()
        self._angular.reset()

    def update(self, wheel_radps: float, steering_rad: float, dt_s: float) -> None:
        rim_mps = wheel_radps * self.wheel_radius_m
        forward = rim_mps * math.cos(steering_rad)
        turn = rim_mps * math.sin(steering_rad) / self.wheelbase_m
        self.pose.advance(forward * dt_s, turn * dt_s)
        self._linear.accumulate(forward)
        self._angular.accumulate(turn)
        self.linear_mps, self.angular_radps = self._linear.mean, self._angular.mean

    def update_open_loop(self, linear_mps: float, angular_radps: float, dt_s: float) -> None:
        self.linear_mps, self.angular_radps = linear_mps, angular_radps
        self.pose.advance(linear_mps * dt_s, angular_radps * dt_s)
