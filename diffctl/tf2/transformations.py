"""tf_transformations' API (the ROS 2 package of tf's transformations.py): 4x4 homogeneous matrices, Euler angles
in any of the 24 axis conventions, quaternions as [x, y, z, w] (tf's order), all on numpy.

Axis conventions are four letters: 's' (static, extrinsic axes) or 'r' (rotating, intrinsic axes) and the three
axes in the order the angles apply. A rotating sequence IJK with angles (a, b, c) is the static sequence KJI with
angles (c, b, a), so everything below works on static sequences: R = R_K(c) · R_J(b) · R_I(a).
Quaternions from matrices are returned with w >= 0, as Jazzy's tf_transformations (over transforms3d) returns them.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence

import numpy as np

_EPS = np.finfo(float).eps * 4.0

_AXES = "xyz"


def _axis_tuples() -> dict[str, tuple[int, int, int, int]]:
    """Euler conventions as tf's (first axis, parity, repetition, frame) tuples: a rotating-frame sequence is
    the static one read backwards."""
    table = {}
    for a, b, c in itertools.product(range(3), repeat=3):
        if a == b or b == c:
            continue
        static = _AXES[a] + _AXES[b] + _AXES[c]
        code = (a, 0 if b == (a + 1) % 3 else 1, int(c == a))
        table["s" + static] = (*code, 0)
        table["r" + static[::-1]] = (*code, 1)
    return table


_AXES2TUPLE = _axis_tuples()
_TUPLE2AXES = {v: k for k, v in _AXES2TUPLE.items()}


def _parse_axes(axes: str | tuple[int, int, int, int]) -> tuple[list[int], bool]:
    """The static axis sequence [I, J, K] (K == I for proper Euler angles) and whether the angles reverse;
    a convention may be given by name or by its tuple."""
    if isinstance(axes, tuple):
        axes = _TUPLE2AXES.get(axes, "")
    name = axes.lower() if isinstance(axes, str) else ""
    seq = [_AXES.index(c) for c in name[1:] if c in _AXES]
    if len(name) != 4 or name[0] not in "sr" or len(seq) != 3 or seq[0] == seq[1] or seq[1] == seq[2]:
        raise KeyError(axes)  # tf's own lookup of an unknown convention raises KeyError too
    return (seq[::-1], True) if name[0] == "r" else (seq, False)


def _axis_rotation(axis: int, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    m = np.identity(3)
    a, b = (axis + 1) % 3, (axis + 2) % 3
    m[a, a] = c
    m[b, b] = c
    m[b, a] = s
    m[a, b] = -s
    return m


def _axis_quaternion(axis: int, angle: float) -> np.ndarray:
    q = np.zeros(4)
    q[axis] = math.sin(angle / 2.0)
    q[3] = math.cos(angle / 2.0)
    return q


def identity_matrix() -> np.ndarray:
    return np.identity(4)


def translation_matrix(direction: Sequence[float]) -> np.ndarray:
    m = np.identity(4)
    m[:3, 3] = np.asarray(direction, dtype=float)[:3]
    return m


def translation_from_matrix(matrix: np.ndarray) -> np.ndarray:
    return np.array(matrix, dtype=float)[:3, 3].copy()


def vector_norm(data: Sequence[float] | np.ndarray, axis: int | None = None,
                out: np.ndarray | None = None) -> float | np.ndarray | None:
    """Euclidean length (along `axis`); with `out`, written there and None returned, as tf's does."""
    arr = np.asarray(data, dtype=float)
    if axis is None and out is None:
        return float(math.sqrt(float(np.dot(arr.ravel(), arr.ravel()))))
    norms = np.sqrt(np.sum(arr * arr, axis=axis))
    if out is None:
        return norms
    out[...] = norms
    return None


def unit_vector(data: Sequence[float] | np.ndarray, axis: int | None = None,
                out: np.ndarray | None = None) -> np.ndarray | None:
    """`data` divided by its length (along `axis`); with `out`, written there and None returned."""
    arr = np.array(data, dtype=float)
    norm = vector_norm(arr, axis)
    if axis is not None:
        norm = np.expand_dims(norm, axis)
    if out is None:
        return arr / norm
    out[...] = arr / norm
    return None


def rotation_matrix(angle: float, direction: Sequence[float], point: Sequence[float] | None = None) -> np.ndarray:
    """The 4x4 rotation by `angle` about the axis along `direction` through `point` (Rodrigues' formula)."""
    u = unit_vector(np.asarray(direction, dtype=float)[:3])
    k = np.array([[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]])
    r = np.identity(3) + math.sin(angle) * k + (1.0 - math.cos(angle)) * (k @ k)
    m = np.identity(4)
    m[:3, :3] = r
    if point is not None:
        p = np.asarray(point, dtype=float)[:3]
        m[:3, 3] = p - r @ p
    return m


def euler_matrix(ai: float, aj: float, ak: float, axes: str = "sxyz") -> np.ndarray:
    seq, reverse = _parse_axes(axes)
    angles = (ak, aj, ai) if reverse else (ai, aj, ak)
    r = _axis_rotation(seq[2], angles[2]) @ _axis_rotation(seq[1], angles[1]) @ _axis_rotation(seq[0], angles[0])
    m = np.identity(4)
    m[:3, :3] = r
    return m


def _parity(i: int, j: int) -> float:
    """+1 when j follows i in x → y → z → x, else -1."""
    return 1.0 if (j - i) % 3 == 1 else -1.0


def euler_from_matrix(matrix: np.ndarray, axes: str = "sxyz") -> tuple[float, float, float]:
    seq, reverse = _parse_axes(axes)
    m = np.asarray(matrix, dtype=float)[:3, :3]
    i, j, k = seq
    s = _parity(i, j)
    if i != k:
        # R = R_k(c) R_j(b) R_i(a): row k, column i holds -s·sin(b)
        cb = math.hypot(m[i, i], m[j, i])
        b = math.atan2(-s * m[k, i], cb)
        if cb > _EPS:
            a = math.atan2(s * m[k, j], m[k, k])
            c = math.atan2(s * m[j, i], m[i, i])
        else:  # gimbal lock: the last angle is taken as 0
            a = math.atan2(-s * m[j, k], m[j, j])
            c = 0.0
    else:
        # proper Euler angles R = R_i(c) R_j(b) R_i(a); l is the third axis
        ll = 3 - i - j
        sb = math.hypot(m[i, j], m[i, ll])
        b = math.atan2(sb, m[i, i])
        if sb > _EPS:
            a = math.atan2(m[i, j], s * m[i, ll])
            c = math.atan2(m[j, i], -s * m[ll, i])
        else:
            a = math.atan2(-s * m[j, ll], m[j, j])
            c = 0.0
    return (c, b, a) if reverse else (a, b, c)


def quaternion_from_euler(ai: float, aj: float, ak: float, axes: str = "sxyz") -> np.ndarray:
    seq, reverse = _parse_axes(axes)
    angles = (ak, aj, ai) if reverse else (ai, aj, ak)
    q = _axis_quaternion(seq[0], angles[0])
    for axis, angle in zip(seq[1:], angles[1:], strict=True):
        q = quaternion_multiply(_axis_quaternion(axis, angle), q)
    return q


def quaternion_matrix(quaternion: Sequence[float]) -> np.ndarray:
    q = np.array(quaternion[:4], dtype=float)
    n = float(np.dot(q, q))
    m = np.identity(4)
    if n < _EPS:
        return m
    x, y, z, w = q * math.sqrt(2.0 / n)
    m[:3, :3] = [
        [1.0 - y * y - z * z, x * y - z * w, x * z + y * w],
        [x * y + z * w, 1.0 - x * x - z * z, y * z - x * w],
        [x * z - y * w, y * z + x * w, 1.0 - x * x - y * y],
    ]
    return m


def quaternion_from_matrix(matrix: np.ndarray) -> np.ndarray:
    """The unit quaternion of the rotation part, w >= 0: the eigenvector of the largest eigenvalue of the
    symmetric 4x4 matrix built from the rotation (robust when the matrix is not quite orthonormal)."""
    m = np.asarray(matrix, dtype=float)[:3, :3]
    xx, xy, xz = m[0]
    yx, yy, yz = m[1]
    zx, zy, zz = m[2]
    k = (
        np.array(
            [
                [xx - yy - zz, yx + xy, zx + xz, zy - yz],
                [yx + xy, yy - xx - zz, zy + yz, xz - zx],
                [zx + xz, zy + yz, zz - xx - yy, yx - xy],
                [zy - yz, xz - zx, yx - xy, xx + yy + zz],
            ]
        )
        / 3.0
    )
    values, vectors = np.linalg.eigh(k)
    q = vectors[:, int(np.argmax(values))]
    if q[3] < 0:
        q = -q
    return q / np.linalg.norm(q)


def euler_from_quaternion(quaternion: Sequence[float], axes: str = "sxyz") -> tuple[float, float, float]:
    return euler_from_matrix(quaternion_matrix(quaternion), axes)


def quaternion_about_axis(angle: float, axis: Sequence[float]) -> np.ndarray:
    q = np.zeros(4)
    v = np.asarray(axis, dtype=float)[:3]
    n = vector_norm(v)
    if n > _EPS:
        q[:3] = v * (math.sin(angle / 2.0) / n)
    q[3] = math.cos(angle / 2.0)
    return q


def quaternion_multiply(quaternion1: Sequence[float], quaternion0: Sequence[float]) -> np.ndarray:
    """quaternion1 · quaternion0 (Hamilton product, [x, y, z, w])."""
    x1, y1, z1, w1 = (float(v) for v in quaternion1[:4])
    x0, y0, z0, w0 = (float(v) for v in quaternion0[:4])
    return np.array(
        [
            w1 * x0 + x1 * w0 + y1 * z0 - z1 * y0,
            w1 * y0 - x1 * z0 + y1 * w0 + z1 * x0,
            w1 * z0 + x1 * y0 - y1 * x0 + z1 * w0,
            w1 * w0 - x1 * x0 - y1 * y0 - z1 * z0,
        ]
    )


def quaternion_conjugate(quaternion: Sequence[float]) -> np.ndarray:
    q = np.array(quaternion[:4], dtype=float)
    q[:3] = -q[:3]
    return q


def quaternion_inverse(quaternion: Sequence[float]) -> np.ndarray:
    q = quaternion_conjugate(quaternion)
    return q / float(np.dot(q, q))


def quaternion_real(quaternion: Sequence[float]) -> float:
    return float(quaternion[3])


def quaternion_imag(quaternion: Sequence[float]) -> np.ndarray:
    return np.array(quaternion[:3], dtype=float)


def quaternion_slerp(
    quat0: Sequence[float], quat1: Sequence[float], fraction: float, spin: int = 0, shortestpath: bool = True
) -> np.ndarray:
    q0 = unit_vector(quat0[:4])
    q1 = unit_vector(quat1[:4])
    if fraction == 0.0:
        return q0
    if fraction == 1.0:
        return q1
    d = float(np.dot(q0, q1))
    if abs(abs(d) - 1.0) < _EPS:
        return q0
    if shortestpath and d < 0.0:
        d, q1 = -d, -q1
    angle = math.acos(max(-1.0, min(1.0, d))) + spin * math.pi
    if abs(angle) < _EPS:
        return q0
    inv_sin = 1.0 / math.sin(angle)
    return (math.sin((1.0 - fraction) * angle) * q0 + math.sin(fraction * angle) * q1) * inv_sin


def inverse_matrix(matrix: np.ndarray) -> np.ndarray:
    return np.linalg.inv(matrix)


def concatenate_matrices(*matrices: np.ndarray) -> np.ndarray:
    m = np.identity(4)
    for other in matrices:
        m = m @ np.asarray(other, dtype=float)
    return m


def is_same_transform(matrix0: np.ndarray, matrix1: np.ndarray) -> bool:
    a = np.array(matrix0, dtype=float)
    b = np.array(matrix1, dtype=float)
    return bool(np.allclose(a / a[3, 3], b / b[3, 3]))


__all__ = [
    "concatenate_matrices",
    "euler_from_matrix",
    "euler_from_quaternion",
    "euler_matrix",
    "identity_matrix",
    "inverse_matrix",
    "is_same_transform",
    "quaternion_about_axis",
    "quaternion_conjugate",
    "quaternion_from_euler",
    "quaternion_from_matrix",
    "quaternion_imag",
    "quaternion_inverse",
    "quaternion_matrix",
    "quaternion_multiply",
    "quaternion_real",
    "quaternion_slerp",
    "rotation_matrix",
    "translation_from_matrix",
    "translation_matrix",
    "unit_vector",
    "vector_norm",
]
