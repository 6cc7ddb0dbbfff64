"""tf2_echo's printout of one transform, as tf2_echo.cpp writes it (std::fixed, 3 decimals), with tf2's
Matrix3x3 (setRotation, getEulerYPR) for the matrix and the roll, pitch and yaw. Pure."""

from __future__ import annotations

import math

Vec = tuple[float, float, float]
Quat = tuple[float, float, float, float]


def matrix_from_quaternion(q: Quat) -> list[list[float]]:
    """tf2::Matrix3x3::setRotation (the quaternion need not be unit: it is divided by its squared norm)."""
    x, y, z, w = q
    s = 2.0 / (x * x + y * y + z * z + w * w)
    xs, ys, zs = x * s, y * s, z * s
    wx, wy, wz = w * xs, w * ys, w * zs
    xx, xy, xz = x * xs, x * ys, x * zs
    yy, yz, zz = y * ys, y * zs, z * zs
    return [
        [1.0 - (yy + zz), xy - wz, xz + wy],
        [xy + wz, 1.0 - (xx + zz), yz - wx],
        [xz - wy, yz + wx, 1.0 - (xx + yy)],
    ]


def euler_ypr(m: list[list[float]]) -> tuple[float, float, float]:
    """tf2::Matrix3x3::getEulerYPR (solution 1): (yaw, pitch, roll)."""
    if abs(m[2][0]) >= 1.0:
        yaw = 0.0
        if m[2][0] < 0.0:  # gimbal locked down
            return yaw, math.pi / 2.0, math.atan2(m[0][1], m[0][2])
        return yaw, -math.pi / 2.0, math.atan2(-m[0][1], -m[0][2])
    pitch = -math.asin(m[2][0])
    c = math.cos(pitch)
    return math.atan2(m[1][0] / c, m[0][0] / c), pitch, math.atan2(m[2][1] / c, m[2][2] / c)


def _f(v: float) -> str:
    return f"{v:.3f}"


def echo_block(stamp_sec: int, stamp_nanosec: int, translation: Vec, rotation: Quat) -> str:
    """The lines tf2_echo prints for one lookup (ending in a newline)."""
    m = matrix_from_quaternion(rotation)
    yaw, pitch, roll = euler_ypr(m)
    deg = 180.0 / math.pi
    lines = [
        f"At time {stamp_sec}.{stamp_nanosec}",
        f"- Translation: [{', '.join(_f(v) for v in translation)}]",
        f"- Rotation: in Quaternion [{', '.join(_f(v) for v in rotation)}]",
        f"- Rotation: in RPY (radian) [{_f(roll)}, {_f(pitch)}, {_f(yaw)}]",
        f"- Rotation: in RPY (degree) [{_f(roll * deg)}, {_f(pitch * deg)}, {_f(yaw * deg)}]",
        "- Matrix:",
    ]
    for i in range(3):
        lines.append("".join(f" {v:6.3f}" for v in m[i]) + f" {translation[i]:6.3f}")
    lines.append("".join(f" {0.0:6.3f}" for _ in range(3)) + f" {1.0:6.3f}")
    return "\n".join(lines) + "\n"
