"""interactive_marker_twist_server's rule, pure: where the marker was dragged to → the Twist to send.

The yaw the marker was turned by, times 2.2, clamped to ±2.2 rad/s, is the turn rate; each configured linear axis
is its displacement times its linear_scale, clamped to [max_negative, max_positive] (an axis without limits
clamps to 0, as the node's maps read missing keys as 0).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

ANGULAR_SCALE = 2.2
MAX_ANGULAR = 2.2
AXES = ("x", "y", "z")


@dataclass(frozen=True)
class Scales:
    linear: dict[str, float]
    max_positive: dict[str, float]
    max_negative: dict[str, float]


DEFAULT = Scales({"x": 1.0}, {"x": 1.0}, {"x": -1.0})


def yaw_of(q: tuple[float, float, float, float]) -> float:
    x, y, z, w = q
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def twist(scales: Scales, position: tuple[float, float, float],
          orientation: tuple[float, float, float, float]) -> tuple[tuple[float, float, float], float]:
    """((linear x, y, z), angular z)."""
    angular = max(-MAX_ANGULAR, min(ANGULAR_SCALE * yaw_of(orientation), MAX_ANGULAR))
    linear = []
    for axis, displacement in zip(AXES, position, strict=True):
        if axis not in scales.linear:
            linear.append(0.0)
            continue
        v = min(scales.linear[axis] * displacement, scales.max_positive.get(axis, 0.0))
        linear.append(max(v, scales.max_negative.get(axis, 0.0)))
    return (linear[0], linear[1], linear[2]), angular
