"""Independent numpy transforms for checking resolved poses (no diffctl code involved)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np


def rot_np(roll: float, pitch: float, yaw: float) -> np.ndarray:
    cx, sx, cy, sy = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch)
    cz, sz = math.cos(yaw), math.sin(yaw)
    rx = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    rz = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    return rz @ ry @ rx


def mat_np(xyz: Sequence[float], rpy: Sequence[float]) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3] = rot_np(*rpy)
    m[:3, 3] = xyz
    return m
