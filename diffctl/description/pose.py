"""Rigid transforms for SDF frames: Pose (translation in metres + unit quaternion xyzw), composition, inverse.

Pure math, no I/O. Conventions follow SDF / ROS: roll-pitch-yaw are extrinsic X-Y-Z rotations (R = Rz·Ry·Rx),
quaternions are (x, y, z, w), `a * b` maps frame-b coordinates through a (the pose of b expressed in a's parent).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

Vec3 = tuple[float, float, float]
Quat = tuple[float, float, float, float]


def quat_from_rpy(roll_rad: float, pitch_rad: float, yaw_rad: float) -> Quat:
    cr, sr = math.cos(roll_rad / 2), math.sin(roll_rad / 2)
    cp, sp = math.cos(pitch_rad / 2), math.sin(pitch_rad / 2)
    cy, sy = math.cos(yaw_rad / 2), math.sin(yaw_rad / 2)
    return (
        sr * cp * cy - cr * sp * sy,
        cr * sp * cy + sr * cp * sy,
        cr * cp * sy - sr * sp * cy,
        cr * cp * cy + sr * sp * sy,
    )


def quat_from_axis_angle(axis: Sequence[float], angle_rad: float) -> Quat:
    """Rotation by `angle_rad` about the unit vector `axis` (right-hand rule); none about a zero axis (as KDL,
    for a URDF joint whose axis urdfdom kept at 0 0 0)."""
    if not any(axis):
        return (0.0, 0.0, 0.0, 1.0)
    s = math.sin(angle_rad / 2)
    return (axis[0] * s, axis[1] * s, axis[2] * s, math.cos(angle_rad / 2))


def rpy_from_quat(q: Quat) -> Vec3:
    x, y, z, w = q
    roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    sinp = 2 * (w * y - z * x)
    # Clamp: rounding can push |sinp| past 1 at the gimbal-lock poles.
    pitch = math.copysign(math.pi / 2, sinp) if abs(sinp) >= 1 else math.asin(sinp)
    yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return (roll, pitch, yaw)


def quat_multiply(a: Quat, b: Quat) -> Quat:
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    )


def quat_normalize(q: Sequence[float]) -> Quat:
    # the sum written out: the same additions in the same order as sum() over the squares, without a generator
    # (an IMU normalizes one per sample)
    x, y, z, w = q
    n = math.sqrt(x * x + y * y + z * z + w * w)
    if n == 0.0 or not math.isfinite(n):
        raise ValueError(f"quaternion {tuple(q)} cannot be normalized")
    return (q[0] / n, q[1] / n, q[2] / n, q[3] / n)


def quat_rotate(q: Quat, v: Sequence[float]) -> Vec3:
    # v' = v + 2w(u×v) + 2u×(u×v), u = vector part: cheaper than building the matrix.
    x, y, z, w = q
    vx, vy, vz = v
    tx = 2 * (y * vz - z * vy)
    ty = 2 * (z * vx - x * vz)
    tz = 2 * (x * vy - y * vx)
    return (
        vx + w * tx + (y * tz - z * ty),
        vy + w * ty + (z * tx - x * tz),
        vz + w * tz + (x * ty - y * tx),
    )


def quat_to_matrix(q: Quat) -> tuple[Vec3, Vec3, Vec3]:
    x, y, z, w = q
    return (
        (1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)),
        (2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)),
        (2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)),
    )


def quat_from_matrix(m: Sequence[Sequence[float]]) -> Quat:
    # Shepperd's method: pick the largest diagonal term for numerical stability.
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0:
        s = math.sqrt(trace + 1.0) * 2
        q = ((m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s)
    elif m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]) * 2
        q = (0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[2][1] - m[1][2]) / s)
    elif m[1][1] > m[2][2]:
        s = math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]) * 2
        q = ((m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s, (m[0][2] - m[2][0]) / s)
    else:
        s = math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]) * 2
        q = ((m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s, (m[1][0] - m[0][1]) / s)
    q = quat_normalize(q)
    return q if q[3] >= 0 else (-q[0], -q[1], -q[2], -q[3])


@dataclass(frozen=True)
class Pose:
    """A rigid transform: position in metres and orientation as a unit quaternion (x, y, z, w)."""

    xyz: Vec3 = (0.0, 0.0, 0.0)
    quat: Quat = (0.0, 0.0, 0.0, 1.0)

    @staticmethod
    def identity() -> Pose:
        return Pose()

    @staticmethod
    def from_xyz_rpy(xyz: Sequence[float], rpy_rad: Sequence[float] = (0.0, 0.0, 0.0)) -> Pose:
        return Pose((float(xyz[0]), float(xyz[1]), float(xyz[2])), quat_from_rpy(*rpy_rad))

    @staticmethod
    def from_matrix(m: Sequence[Sequence[float]]) -> Pose:
        """From a 4x4 homogeneous matrix (nested sequences or a numpy array)."""
        return Pose((float(m[0][3]), float(m[1][3]), float(m[2][3])), quat_from_matrix([row[:3] for row in m[:3]]))

    @property
    def rpy(self) -> Vec3:
        return rpy_from_quat(self.quat)

    def to_matrix(self) -> list[list[float]]:
        r = quat_to_matrix(self.quat)
        return [[*r[0], self.xyz[0]], [*r[1], self.xyz[1]], [*r[2], self.xyz[2]], [0.0, 0.0, 0.0, 1.0]]

    def compose(self, other: Pose) -> Pose:
        """self ∘ other: `other` is expressed in self's frame; the result is in self's parent frame."""
        t = quat_rotate(self.quat, other.xyz)
        x, y, z, w = quat_multiply(self.quat, other.quat)
        n = math.sqrt(x * x + y * y + z * z + w * w)  # hot: TF, sensors; no generator
        return Pose(
            (self.xyz[0] + t[0], self.xyz[1] + t[1], self.xyz[2] + t[2]),
            (x / n, y / n, z / n, w / n),
        )

    __mul__ = compose

    def inverse(self) -> Pose:
        qi = (-self.quat[0], -self.quat[1], -self.quat[2], self.quat[3])
        t = quat_rotate(qi, self.xyz)
        return Pose((-t[0], -t[1], -t[2]), qi)

    def transform_point(self, p: Sequence[float]) -> Vec3:
        r = quat_rotate(self.quat, p)
        return (r[0] + self.xyz[0], r[1] + self.xyz[1], r[2] + self.xyz[2])

    def rotate(self, v: Sequence[float]) -> Vec3:
        return quat_rotate(self.quat, v)

    def relative_to(self, base: Pose) -> Pose:
        """This pose expressed in `base`'s frame (both given in the same parent frame)."""
        return base.inverse().compose(self)

    def is_close(self, other: Pose, tol: float = 1e-9) -> bool:
        """Same transform within `tol` (q and -q are the same rotation)."""
        if any(abs(a - b) > tol for a, b in zip(self.xyz, other.xyz, strict=True)):
            return False
        sign = 1.0 if sum(a * b for a, b in zip(self.quat, other.quat, strict=True)) >= 0 else -1.0
        return all(abs(a - sign * b) <= tol for a, b in zip(self.quat, other.quat, strict=True))

    def __repr__(self) -> str:
        r = self.rpy
        return (
            f"Pose(xyz=({self.xyz[0]:.6g}, {self.xyz[1]:.6g}, {self.xyz[2]:.6g}), "
            f"rpy=({r[0]:.6g}, {r[1]:.6g}, {r[2]:.6g}))"
        )
