"""Rotations and rigid transforms as numpy arrays, with tf2's conventions (fixed-axis roll, pitch, yaw)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


def rot_x(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array(((1.0, 0.0, 0.0), (0.0, c, -s), (0.0, s, c)))


def rot_y(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array(((c, 0.0, s), (0.0, 1.0, 0.0), (-s, 0.0, c)))


def rot_z(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array(((c, -s, 0.0), (s, c, 0.0), (0.0, 0.0, 1.0)))


def from_rpy(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """Rz(yaw)·Ry(pitch)·Rx(roll): body axes to world axes."""
    return rot_z(yaw) @ rot_y(pitch) @ rot_x(roll)


def to_rpy(m: np.ndarray) -> tuple[float, float, float]:
    """(roll, pitch, yaw) of a rotation matrix, the first of tf2's two solutions (pitch in [-π/2, π/2])."""
    if abs(m[2, 0]) >= 1.0:
        # Gimbal lock: yaw is taken as zero and roll carries the whole rotation about the vertical.
        if m[2, 0] < 0.0:
            return math.atan2(m[0, 1], m[0, 2]), math.pi / 2, 0.0
        return math.atan2(-m[0, 1], -m[0, 2]), -math.pi / 2, 0.0
    pitch = -math.asin(m[2, 0])
    c = math.cos(pitch)
    return math.atan2(m[2, 1] / c, m[2, 2] / c), pitch, math.atan2(m[1, 0] / c, m[0, 0] / c)


def from_quat(x: float, y: float, z: float, w: float) -> np.ndarray:
    """The rotation of a quaternion (scaled by its norm, so a slightly denormalized one still rotates)."""
    n = x * x + y * y + z * z + w * w
    s = 2.0 / n if n > 0.0 else 0.0
    xs, ys, zs = x * s, y * s, z * s
    wx, wy, wz = w * xs, w * ys, w * zs
    xx, xy, xz = x * xs, x * ys, x * zs
    yy, yz, zz = y * ys, y * zs, z * zs
    return np.array(((1.0 - (yy + zz), xy - wz, xz + wy),
                     (xy + wz, 1.0 - (xx + zz), yz - wx),
                     (xz - wy, yz + wx, 1.0 - (xx + yy))))


def quat_from_rpy(roll: float, pitch: float, yaw: float) -> tuple[float, float, float, float]:
    """(x, y, z, w) of fixed-axis roll, pitch, yaw."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy)


def quat_from_matrix(m: np.ndarray) -> tuple[float, float, float, float]:
    """(x, y, z, w) of a rotation matrix, w ≥ 0."""
    tr = m[0, 0] + m[1, 1] + m[2, 2]
    if tr > 0.0:
        s = math.sqrt(tr + 1.0) * 2.0
        q = ((m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s, s / 4.0)
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2]) * 2.0
        q = (s / 4.0, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s, (m[2, 1] - m[1, 2]) / s)
    elif m[1, 1] > m[2, 2]:
        s = math.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2]) * 2.0
        q = ((m[0, 1] + m[1, 0]) / s, s / 4.0, (m[1, 2] + m[2, 1]) / s, (m[0, 2] - m[2, 0]) / s)
    else:
        s = math.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1]) * 2.0
        q = ((m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, s / 4.0, (m[1, 0] - m[0, 1]) / s)
    return q if q[3] >= 0.0 else (-q[0], -q[1], -q[2], -q[3])


@dataclass(frozen=True)
class Rigid:
    """A rigid transform: x_target = rot · x_source + trans."""

    rot: np.ndarray
    trans: np.ndarray

    @staticmethod
    def identity() -> Rigid:
        return Rigid(np.eye(3), np.zeros(3))

    @staticmethod
    def from_xyz_quat(xyz: tuple[float, float, float], q: tuple[float, float, float, float]) -> Rigid:
        return Rigid(from_quat(*q), np.array(xyz, dtype=float))

    def __mul__(self, other: Rigid) -> Rigid:
        return Rigid(self.rot @ other.rot, self.rot @ other.trans + self.trans)

    def inverse(self) -> Rigid:
        rt = self.rot.T
        return Rigid(rt, -(rt @ self.trans))

    def rpy(self) -> tuple[float, float, float]:
        return to_rpy(self.rot)

    def quat(self) -> tuple[float, float, float, float]:
        return quat_from_matrix(self.rot)
