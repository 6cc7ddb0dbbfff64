"""Bounds beyond which a velocity command is not a command but garbage, and the check that enforces them.

Controllers drop such commands before they are stored, so non-finite or absurd values never reach the
wheels or the physics, whatever limits (possibly none) the controller is configured with.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

MAX_LINEAR_MPS = 100.0  # a base faster than 360 km/h is a typo or an uninitialised value
MAX_ANGULAR_RADPS = 100.0  # ~16 turns per second
MAX_JOINT_VELOCITY = 1000.0  # rad/s or m/s on a joint interface


def rejection(values: Sequence[float], bounds: Sequence[float], names: Sequence[str]) -> str | None:
    """Why this command must be dropped ("linear.x is nan", "…exceeds…"), or None when it is acceptable."""
    for value, bound, name in zip(values, bounds, names, strict=True):
        if not isinstance(value, int | float) or isinstance(value, bool):
            return f"{name} is {value!r}, not a number"
        value = float(value)  # numpy scalars from array fields would print as np.float64(...)
        if not math.isfinite(value):
            return f"{name} is {value!r}"
        if abs(value) > bound:
            return f"{name} = {value!r} exceeds the sanity bound ±{bound:g}"
    return None
