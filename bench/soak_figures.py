"""Pure figures of the soak run: relative-motion agreement of odometry and ground truth, memory growth.

Poses are (x_m, y_m, yaw_rad) in their own fixed frame (odom for odometry, world for ground truth). The two
frames differ by a constant transform plus the drift open-loop odometry accumulates, so the soak compares the
*motion over a window* expressed in the robot's frame at the window's start — which both must agree on —
instead of absolute positions.
"""

from __future__ import annotations

import math
import statistics
from dataclasses import dataclass

Pose2D = tuple[float, float, float]


def relative_motion(a: Pose2D, b: Pose2D) -> Pose2D:
    """The motion from pose a to pose b, in a's body frame: (forward_m, left_m, turned_rad)."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return (c * dx + s * dy, -s * dx + c * dy, math.remainder(b[2] - a[2], math.tau))


def interpolate(a: Pose2D, b: Pose2D, f: float) -> Pose2D:
    """The pose a fraction f of the way from a to b (yaw along the shorter arc)."""
    return (a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * math.remainder(b[2] - a[2], math.tau))


@dataclass(frozen=True)
class MotionError:
    """How far odometry's motion over one window is from the ground truth's."""

    position_m: float
    yaw_rad: float
    path_m: float  # distance the ground truth covered (for a relative bound)
    turned_rad: float  # total turning of the ground truth, both ways counted

    def within(self, rel: float, abs_m: float, abs_rad: float) -> bool:
        return self.position_m <= rel * self.path_m + abs_m and self.yaw_rad <= rel * abs(self.turned_rad) + abs_rad


def motion_error(
    odom_a: Pose2D, odom_b: Pose2D, truth_a: Pose2D, truth_b: Pose2D, path_m: float, turned_rad: float
) -> MotionError:
    o = relative_motion(odom_a, odom_b)
    t = relative_motion(truth_a, truth_b)
    return MotionError(
        math.hypot(o[0] - t[0], o[1] - t[1]), abs(math.remainder(o[2] - t[2], math.tau)), path_m, turned_rad
    )


def growth_percent(samples_mb: list[float], edge: int = 3) -> float:
    """Growth from the median of the first `edge` samples to the median of the last `edge`, in percent."""
    if len(samples_mb) < 2:
        return 0.0
    k = max(1, min(edge, len(samples_mb) // 2))
    first = statistics.median(samples_mb[:k])
    last = statistics.median(samples_mb[-k:])
    return 0.0 if first <= 0 else (last - first) / first * 100.0
