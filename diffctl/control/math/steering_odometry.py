"""steering_controllers_library's kinematics (Jazzy, SteeringKinematics): car-like bases with one virtual steered
wheel at `wheelbase_m` ahead of the traction axle.

Configurations: BICYCLE (one traction wheel, one steering joint), TRICYCLE (two traction wheels `traction_track_m`
apart, one steering joint), ACKERMANN (two traction wheels, two steering joints `steering_track_m` apart). Wheel
lists are ordered right, left.

Forward kinematics turn wheel speeds (or wheel positions differenced over dt) and steering angles into the base's
forward speed v and turn rate ω = v·tan φ / wheelbase: two traction wheels are each scaled to the axle centre's
radius and averaged; two steering angles are each mapped to the virtual middle wheel's angle and averaged. The pose
integrates along arcs; the reported twist is the rolling mean of the last `window` samples. Inverse kinematics
(`commands`) give the traction wheels' speeds and the steering angles for a twist: the middle angle
φ = atan(ω·L / v) (0 when undefined), the outer and inner wheels scaled by their radii about the turning centre,
and for Ackermann each steering joint's own angle atan2(2L·sin φ, 2L·cos φ ± track·sin φ).
"""

from __future__ import annotations

import math

from diffctl.control.math.planar_pose import PlanarPose
from diffctl.control.math.rolling_mean import RollingMean

BICYCLE, TRICYCLE, ACKERMANN = 0, 1, 2
_NEAR_ZERO = 1e-6
_MIN_DT_S = 0.0001


class SteeringKinematics:
    def __init__(self, window: int = 10) -> None:
        self.config = BICYCLE
        self.wheel_radius_m = self.wheelbase_m = 0.0
        self.traction_track_m = self.steering_track_m = 0.0
        self.pose = PlanarPose()
        self._window = window
        self._linear, self._angular = RollingMean(window), RollingMean(window)
        self.linear_mps = self.angular_radps = 0.0
        self.steering_rad = 0.0  # the virtual middle wheel's angle, last measured
        self._old_positions: tuple[float, ...] = (0.0, 0.0)

    def set_wheel_params(self, wheel_radius_m: float, wheelbase_m: float, steering_track_m: float = 0.0,
                         traction_track_m: float | None = None) -> None:
        self.wheel_radius_m, self.wheelbase_m = wheel_radius_m, wheelbase_m
        self.steering_track_m = steering_track_m
        self.traction_track_m = steering_track_m if traction_track_m is None else traction_track_m

    def set_window(self, window: int) -> None:
        self._window = window
        self._linear, self._angular = RollingMean(window), RollingMean(window)

    def reset(self) -> None:
        self.pose.reset()
        self.set_window(self._window)

    # --- forward kinematics --------------------------------------------------------------------------------
    def _integrate(self, linear_mps: float, angular_radps: float, dt_s: float) -> bool:
        self.pose.advance(linear_mps * dt_s, angular_radps * dt_s)
        if dt_s < _MIN_DT_S:
            return False
        self._linear.accumulate(linear_mps)
        self._angular.accumulate(angular_radps)
        self.linear_mps, self.angular_radps = self._linear.mean, self._angular.mean
        return True

    def _axle_speed(self, right_radps: float, left_radps: float, steering_rad: float) -> float:
        """The traction axle centre's speed from its two wheels (their mean where the arc radii differ)."""
        right_mps, left_mps = right_radps * self.wheel_radius_m, left_radps * self.wheel_radius_m
        tan = math.tan(steering_rad)
        if tan == 0.0:
            return 0.5 * (right_mps + left_mps)
        radius = self.wheelbase_m / tan
        half = 0.5 * self.traction_track_m
        return 0.5 * (right_mps * radius / (radius + half) + left_mps * radius / (radius - half))

    def _middle_angle(self, right_rad: float, left_rad: float) -> float:
        """The virtual middle wheel's angle from the two steered wheels' angles (their mean)."""
        base, half = self.wheelbase_m, 0.5 * self.steering_track_m
        tr, tl = math.tan(right_rad), math.tan(left_rad)
        return 0.5 * (math.atan(base * tr / (base - half * tr)) + math.atan(base * tl / (base + half * tl)))

    def update_from_velocity(self, traction_radps: tuple[float, ...], steering_rad: tuple[float, ...],
                             dt_s: float) -> bool:
        """Traction wheel speeds (one, or right and left) and steering angles (one, or right and left)."""
        phi = steering_rad[0] if len(steering_rad) == 1 else self._middle_angle(*steering_rad)
        self.steering_rad = phi
        if len(traction_radps) == 1:
            linear = traction_radps[0] * self.wheel_radius_m
        else:
            linear = self._axle_speed(traction_radps[0], traction_radps[1], phi)
        return self._integrate(linear, math.tan(phi) * linear / self.wheelbase_m, dt_s)

    def update_from_position(self, traction_rad: tuple[float, ...], steering_rad: tuple[float, ...],
                             dt_s: float) -> bool:
        """As update_from_velocity, the wheel speeds differenced from their positions (the first step counts
        from 0, as upstream)."""
        old = self._old_positions
        speeds = tuple((p - old[k]) / dt_s for k, p in enumerate(traction_rad))
        self._old_positions = tuple(traction_rad) + old[len(traction_rad):]
        return self.update_from_velocity(speeds, steering_rad, dt_s)

    def update_open_loop(self, linear_mps: float, angular_radps: float, dt_s: float) -> None:
        self.linear_mps, self.angular_radps = linear_mps, angular_radps
        self.pose.advance(linear_mps * dt_s, angular_radps * dt_s)

    # --- inverse kinematics ----------------------------------------------------------------------------------
    def middle_angle_for(self, linear_mps: float, angular_radps: float) -> float:
        phi = math.atan(angular_radps * self.wheelbase_m / linear_mps) if linear_mps != 0 else \
            math.copysign(math.pi / 2, angular_radps) if angular_radps != 0 else math.nan
        return phi if math.isfinite(phi) else 0.0

    def commands(self, linear_mps: float, angular_radps: float, open_loop: bool = False,
                 slow_until_steered: bool = False) -> tuple[list[float], list[float]]:
        """(traction wheel speeds rad/s, steering angles rad), each list right then left."""
        phi = self.middle_angle_for(linear_mps, angular_radps)
        phi_ik = phi if open_loop else self.steering_rad
        wheel = linear_mps / self.wheel_radius_m
        if not open_loop and slow_until_steered:
            error = abs(self.steering_rad - phi)
            least, most = math.pi / 6.0, 1.5608
            if error >= least:
                wheel *= math.cos(min(error, most)) / math.cos(least)
        if self.config == BICYCLE:
            return [wheel], [phi]
        if abs(phi_ik) < _NEAR_ZERO:
            traction = [wheel, wheel]
        else:
            radius = self.wheelbase_m / math.tan(phi_ik)
            half = 0.5 * self.traction_track_m
            traction = [wheel * (radius + half) / radius, wheel * (radius - half) / radius]
        if self.config == TRICYCLE:
            return traction, [phi]
        if abs(phi_ik) < _NEAR_ZERO:
            return traction, [phi, phi]
        rise = 2.0 * self.wheelbase_m * math.sin(phi)
        run = 2.0 * self.wheelbase_m * math.cos(phi)
        spread = self.steering_track_m * math.sin(phi)
        return traction, [math.atan2(rise, run + spread), math.atan2(rise, run - spread)]
