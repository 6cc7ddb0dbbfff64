"""Mecanum drive kinematics and odometry (mecanum_drive_controller, Jazzy).

Wheels, in the controller's order: front left, front right, rear right, rear left; their rollers make a body
twist (vx, vy, wz) of the robot's centre need ω = (vx ∓ vy ∓ L·wz) / r with L = lx + ly (the sum of the
centre-to-wheel projections, `sum_of_robot_center_projection_on_X_Y_axis`). The base frame (base_link) may sit
off the centre: `base_offset` (x_m, y_m, theta_rad) is the base frame's pose in the centre frame; commands are
body twists of the base frame and odometry reports the base frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

_MIN_DT_S = 0.0001


@dataclass(frozen=True)
class MecanumGeometry:
    wheel_radius_m: float
    center_projection_sum_m: float  # lx + ly
    base_offset_x_m: float = 0.0
    base_offset_y_m: float = 0.0
    base_offset_theta_rad: float = 0.0


def wheel_velocities_radps(g: MecanumGeometry, vx_mps: float, vy_mps: float, wz_radps: float
                           ) -> tuple[float, float, float, float]:
    """(front left, front right, rear right, rear left) wheel speeds for a base-frame body twist."""
    c, s = math.cos(g.base_offset_theta_rad), math.sin(g.base_offset_theta_rad)
    # the command turned into the centre frame, plus the lever arm of the base frame's offset
    cx = c * vx_mps - s * vy_mps + g.base_offset_y_m * wz_radps
    cy = s * vx_mps + c * vy_mps - g.base_offset_x_m * wz_radps
    spin = g.center_projection_sum_m * wz_radps
    r = g.wheel_radius_m
    return (cx - cy - spin) / r, (cx + cy + spin) / r, (cx - cy + spin) / r, (cx + cy - spin) / r


def body_twist(g: MecanumGeometry, front_left: float, front_right: float, rear_right: float, rear_left: float
               ) -> tuple[float, float, float]:
    """The base frame's body twist (vx_mps, vy_mps, wz_radps) from the four wheel speeds (rad/s)."""
    quarter_r = 0.25 * g.wheel_radius_m
    cx = quarter_r * (front_left + rear_left + rear_right + front_right)
    cy = quarter_r * (rear_left + front_right - front_left - rear_right)
    turn = rear_right + front_right - front_left - rear_left
    wz = quarter_r / g.center_projection_sum_m * turn if g.center_projection_sum_m else math.nan
    c, s = math.cos(g.base_offset_theta_rad), math.sin(g.base_offset_theta_rad)
    # back from the centre frame into the base frame (rotation by −theta), with the offset's lever arm
    vx, vy = c * cx + s * cy, -s * cx + c * cy
    arm_x = -(c * g.base_offset_x_m + s * g.base_offset_y_m)
    arm_y = -(-s * g.base_offset_x_m + c * g.base_offset_y_m)
    return vx + arm_y * wz, vy - arm_x * wz, wz


class MecanumOdometry:
    """Pose (x_m, y_m, heading_rad) of the base frame in the odometry frame, and its last body twist, integrated
    from wheel speeds with Euler steps (the heading first)."""

    def __init__(self, geometry: MecanumGeometry) -> None:
        self.geometry = geometry
        self.x_m = self.y_m = self.heading_rad = 0.0
        self.vx_mps = self.vy_mps = self.wz_radps = 0.0

    def update(self, front_left: float, front_right: float, rear_right: float, rear_left: float,
               dt_s: float) -> bool:
        if dt_s < _MIN_DT_S:
            return False
        vx, vy, wz = body_twist(self.geometry, front_left, front_right, rear_right, rear_left)
        self.vx_mps, self.vy_mps, self.wz_radps = vx, vy, wz
        self.heading_rad += wz * dt_s
        c, s = math.cos(self.heading_rad), math.sin(self.heading_rad)
        self.x_m += (c * vx - s * vy) * dt_s
        self.y_m += (s * vx + c * vy) * dt_s
        return True
