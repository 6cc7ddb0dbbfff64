"""A planar pose (x_m, y_m, heading_rad) moved by body-frame steps: along the arc when the heading changes by at
least 1e-6 rad, else by second-order Runge-Kutta (the arc's radius would blow up), as ros2_controllers' odometries
integrate."""

from __future__ import annotations

import math

_STRAIGHT_RAD = 1e-6


class PlanarPose:
    __slots__ = ("heading_rad", "x_m", "y_m")

    def __init__(self) -> None:
        self.x_m = self.y_m = self.heading_rad = 0.0

    def reset(self) -> None:
        self.x_m = self.y_m = self.heading_rad = 0.0

    def advance(self, forward_m: float, turn_rad: float) -> None:
        """Move `forward_m` along the body's x axis while turning by `turn_rad`."""
        start = self.heading_rad
        if abs(turn_rad) < _STRAIGHT_RAD:
            mid = start + 0.5 * turn_rad
            self.x_m += forward_m * math.cos(mid)
            self.y_m += forward_m * math.sin(mid)
            self.heading_rad = start + turn_rad
            return
        radius = forward_m / turn_rad
        end = start + turn_rad
        self.x_m += radius * (math.sin(end) - math.sin(start))
        self.y_m -= radius * (math.cos(end) - math.cos(start))
        self.heading_rad = end
