"""Rigid transforms as (translation xyz, quaternion xyzw) tuples of floats: composition, inversion,
and the interpolation tf2 uses between two stamps (linear translation, shortest-path slerp)."""

from __future__ import annotations

import math

Vec = tuple[float, float, float]
Quat = tuple[float, float, float, float]  # x, y, z, w
IDENTITY_Q: Quat = (0.0, 0.0, 0.0, 1.0)
ZERO_V: Vec = (0.0, 0.0, 0.0)


def q_mul(a: Quat, b: Quat) -> Quat:
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by + ay * bw + az * bx - ax * bz,
        aw * bz + az * bw + ax * by - ay * bx,
        aw * bw - ax * bx - ay * by - az * bz,
    )


def q_inv(q: Quat) -> Quat:
    # Unit quaternions only (tf2 refuses others on insertion): the conjugate.
    return (-q[0], -q[1], -q[2], q[3])


def rotate(q: Quat, v: Vec) -> Vec:
    x, y, z, w = q
    vx, vy, vz = v
    # v + 2w(u×v) + 2u×(u×v), u = (x, y, z)
    cx, cy, cz = y * vz - z * vy, z * vx - x * vz, x * vy - y * vx
    ccx, ccy, ccz = y * cz - z * cy, z * cx - x * cz, x * cy - y * cx
    return (vx + 2.0 * (w * cx + ccx), vy + 2.0 * (w * cy + ccy), vz + 2.0 * (w * cz + ccz))


def compose(t1: Vec, q1: Quat, t2: Vec, q2: Quat) -> tuple[Vec, Quat]:
    """(t1, q1) ∘ (t2, q2): first t2/q2, then t1/q1 (a point p maps to q1·(q2·p + t2) + t1)."""
    r = rotate(q1, t2)
    return (r[0] + t1[0], r[1] + t1[1], r[2] + t1[2]), q_mul(q1, q2)


def invert(t: Vec, q: Quat) -> tuple[Vec, Quat]:
    qi = q_inv(q)
    r = rotate(qi, t)
    return (-r[0], -r[1], -r[2]), qi


def lerp(a: Vec, b: Vec, ratio: float) -> Vec:
    return (a[0] + (b[0] - a[0]) * ratio, a[1] + (b[1] - a[1]) * ratio, a[2] + (b[2] - a[2]) * ratio)


def slerp(a: Quat, b: Quat, ratio: float) -> Quat:
    """Spherical interpolation along the shorter arc (b is negated when a·b < 0), as tf2's LinearMath."""
    dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
    norms = math.sqrt(sum(c * c for c in a) * sum(c * c for c in b))
    half_angle = math.acos(max(-1.0, min(1.0, abs(dot) / norms)))
    if half_angle == 0.0:
        return a
    inv_sin = 1.0 / math.sin(half_angle)
    s0 = math.sin((1.0 - ratio) * half_angle) * inv_sin
    s1 = math.sin(ratio * half_angle) * inv_sin
    if dot < 0.0:
        s1 = -s1
    return tuple(a[i] * s0 + b[i] * s1 for i in range(4))  # type: ignore[return-value]


def is_normalized(q: Quat, tolerance: float = 10e-3) -> bool:
    return abs(sum(c * c for c in q) - 1.0) < tolerance
