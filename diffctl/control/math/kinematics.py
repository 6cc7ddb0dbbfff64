"""Differential-drive kinematics: wheel speeds from a body twist, and the planar heading as a quaternion."""

from __future__ import annotations

import math


def wheel_velocities_radps(
    linear_mps: float,
    angular_radps: float,
    wheel_separation_m: float,
    left_wheel_radius_m: float,
    right_wheel_radius_m: float,
) -> tuple[float, float]:
    """(left, right) wheel angular velocities that make the base move at (linear, angular)."""
    half_turn_mps = angular_radps * wheel_separation_m / 2.0
    return (
        (linear_mps - half_turn_mps) / left_wheel_radius_m,
        (linear_mps + half_turn_mps) / right_wheel_radius_m,
    )


def heading_quaternion(heading_rad: float) -> tuple[float, float, float, float]:
    """(x, y, z, w) of a rotation by `heading_rad` about +z (roll = pitch = 0)."""
    half = heading_rad * 0.5
    return (0.0, 0.0, math.sin(half), math.cos(half))
