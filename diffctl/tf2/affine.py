"""The rest of tf_transformations: reflections, scaling, shears, projections, clip volumes, decomposition,
crystallographic cells, point-set superimposition and random rotations, on 4x4 homogeneous matrices.

Reflections, rotations about an axis, scaling, shears and decomposition are transforms3d's (the library ROS's
tf_transformations is built on); the rest is plain numpy. Return orders follow tf_transformations (e.g.
`rotation_from_matrix` gives angle, direction, point).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import transforms3d

from diffctl.tf2.transformations import _AXES2TUPLE, _TUPLE2AXES, euler_from_matrix, quaternion_matrix  # noqa: F401

_TINY = 4.0 * np.finfo(float).eps




def reflection_matrix(point: Sequence[float], normal: Sequence[float]) -> np.ndarray:
    """Mirror at the plane through `point` with `normal`."""
    return transforms3d.reflections.rfnorm2aff(np.asarray(normal, dtype=float)[:3],
                                               np.asarray(point, dtype=float)[:3])


def reflection_from_matrix(matrix: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(point, normal) of a reflection matrix's plane."""
    normal, point = transforms3d.reflections.aff2rfnorm(np.asarray(matrix, dtype=float))
    return point, normal


def rotation_from_matrix(matrix: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
    """(angle, direction, point) of a rotation about an axis."""
    direction, angle, point = transforms3d.axangles.aff2axangle(np.asarray(matrix, dtype=float))
    return angle, direction, point


def scale_matrix(factor: float, origin: Sequence[float] | None = None,
                 direction: Sequence[float] | None = None) -> np.ndarray:
    """Scale by `factor` about `origin`, along `direction` only when given (-1: point symmetry)."""
    return transforms3d.zooms.zfdir2aff(
        factor, direction=None if direction is None else np.asarray(direction, dtype=float)[:3],
        origin=None if origin is None else np.asarray(origin, dtype=float)[:3])


def scale_from_matrix(matrix: np.ndarray) -> tuple[float, np.ndarray, np.ndarray | None]:
    """(factor, origin, direction) of a scaling matrix (direction None for uniform scaling)."""
    factor, direction, origin = transforms3d.zooms.aff2zfdir(np.asarray(matrix, dtype=float))
    return factor, origin, direction


def shear_matrix(angle: float, direction: Sequence[float], point: Sequence[float],
                 normal: Sequence[float]) -> np.ndarray:
    """Shear by `angle` along `direction` (orthogonal to `normal`) on the plane through `point`."""
    return transforms3d.shears.sadn2aff(angle, np.asarray(direction, dtype=float)[:3],
                                        np.asarray(normal, dtype=float)[:3], np.asarray(point, dtype=float)[:3])


def shear_from_matrix(matrix: np.ndarray) -> tuple[float, np.ndarray, np.ndarray, np.ndarray]:
    """(angle, direction, point, normal) of a shear matrix."""
    angle, direction, normal, point = transforms3d.shears.aff2sadn(np.asarray(matrix, dtype=float))
    return angle, direction, point, normal


def decompose_matrix(matrix: np.ndarray) -> tuple[np.ndarray, np.ndarray, tuple[float, float, float],
                                                  np.ndarray, None]:
    """(scale, shear, static-xyz Euler angles, translation, perspective) of an affine matrix; the perspective
    part is not extracted (None), as in ROS's module."""
    translation, rotation, zooms, shears = transforms3d.affines.decompose(np.asarray(matrix, dtype=float))
    return zooms, shears, euler_from_matrix(rotation), translation, None


def compose_matrix(scale: Sequence[float] | None = None, shear: Sequence[float] | None = None,
                   angles: Sequence[float] | None = None, translate: Sequence[float] | None = None,
                   perspective: Sequence[float] | None = None) -> np.ndarray:
    """The inverse of decompose_matrix (the perspective part is ignored, as in ROS's module)."""
    rotation = np.eye(3) if angles is None else transforms3d.euler.euler2mat(*angles)
    return transforms3d.affines.compose(
        np.zeros(3) if translate is None else np.asarray(translate, dtype=float)[:3], rotation,
        np.ones(3) if scale is None else np.asarray(scale, dtype=float)[:3],
        np.zeros(3) if shear is None else np.asarray(shear, dtype=float)[:3])


def _unit(v: np.ndarray) -> np.ndarray:
    return v / math.sqrt(float(np.dot(v, v)))


def projection_matrix(point: Sequence[float], normal: Sequence[float], direction: Sequence[float] | None = None,
                      perspective: Sequence[float] | None = None, pseudo: bool = False) -> np.ndarray:
    """Projection onto the plane through `point` with `normal`: from a `perspective` point, along `direction`
    (parallel), or orthogonal when neither is given; `pseudo` keeps relative depth in a perspective one."""
    p = np.asarray(point, dtype=float)[:3]
    n = _unit(np.asarray(normal, dtype=float)[:3])
    plane_offset = float(np.dot(p, n))
    out = np.eye(4)
    if perspective is not None:
        eye = np.asarray(perspective, dtype=float)[:3]
        out[:3, :3] = float(np.dot(eye - p, n)) * np.eye(3) - np.outer(eye, n)
        if pseudo:
            out[:3, :3] -= np.outer(n, n)
            out[:3, 3] = plane_offset * (eye + n)
        else:
            out[:3, 3] = plane_offset * eye
        out[3, :3] = -n
        out[3, 3] = float(np.dot(eye, n))
        return out
    along = n if direction is None else np.asarray(direction, dtype=float)[:3]
    along_normal = float(np.dot(along, n))
    out[:3, :3] -= np.outer(along, n) / along_normal
    out[:3, 3] = along * (plane_offset / along_normal)
    return out


def _eigenvectors(matrix: np.ndarray, keep) -> np.ndarray:
    values, vectors = np.linalg.eig(matrix)
    return np.real(vectors[:, [i for i, v in enumerate(values) if keep(v)]])


def projection_from_matrix(matrix: np.ndarray, pseudo: bool = False) -> tuple:
    """projection_matrix's arguments (point, normal, direction, perspective, pseudo) back from its matrix."""
    m = np.asarray(matrix, dtype=float)
    fixed = _eigenvectors(m, lambda v: abs(v.real - 1.0) < 1e-8)
    if not pseudo and fixed.shape[1]:
        point = fixed[:, -1] / fixed[-1, -1]
        collapsed = _eigenvectors(m[:3, :3], lambda v: abs(v.real) < 1e-8)
        if not collapsed.shape[1]:
            raise ValueError("no eigenvector corresponding to eigenvalue 0")
        direction = _unit(collapsed[:, 0])
        normals = _eigenvectors(m[:3, :3].T, lambda v: abs(v.real) < 1e-8)
        if normals.shape[1]:
            return point, _unit(normals[:, 0]), direction, None, False
        return point, direction, None, None, False
    kept = _eigenvectors(m, lambda v: abs(v.real) > 1e-8)
    if not kept.shape[1]:
        raise ValueError("no eigenvector not corresponding to eigenvalue 0")
    point = kept[:, -1] / kept[-1, -1]
    normal = -m[3, :3]
    eye = m[:3, 3] / float(np.dot(point[:3], normal))
    if pseudo:
        eye = eye - normal
    return point, normal, None, eye, pseudo


def clip_matrix(left: float, right: float, bottom: float, top: float, near: float, far: float,
                perspective: bool = False) -> np.ndarray:
    """Frustum (perspective, apex at the origin looking down z) or box → normalized device coordinates in
    [-1, 1]; perspective results need dividing by w."""
    if left >= right or bottom >= top or near >= far:
        raise ValueError("invalid frustrum")
    width, height, depth = right - left, top - bottom, far - near
    out = np.zeros((4, 4))
    if perspective:
        if near <= _TINY:
            raise ValueError("invalid frustum: near <= 0")
        out[0, 0], out[0, 2] = -2.0 * near / width, (right + left) / width
        out[1, 1], out[1, 2] = -2.0 * near / height, (top + bottom) / height
        out[2, 2], out[2, 3] = -(far + near) / depth, 2.0 * near * far / depth
        out[3, 2] = -1.0
    else:
        out[0, 0], out[0, 3] = 2.0 / width, -(right + left) / width
        out[1, 1], out[1, 3] = 2.0 / height, -(top + bottom) / height
        out[2, 2], out[2, 3] = 2.0 / depth, -(far + near) / depth
        out[3, 3] = 1.0
    return out


def orthogonalization_matrix(lengths: Sequence[float], angles: Sequence[float]) -> np.ndarray:
    """Crystallographic cell (edge lengths, angles in degrees) → Cartesian; its inverse de-orthogonalizes."""
    a, b, c = lengths
    alpha, beta, gamma = np.radians(angles)
    cos_star = (math.cos(alpha) * math.cos(beta) - math.cos(gamma)) / (math.sin(alpha) * math.sin(beta))
    out = np.eye(4)
    out[:3, :3] = [
        [a * math.sin(beta) * math.sqrt(1.0 - cos_star**2), 0.0, 0.0],
        [-a * math.sin(beta) * cos_star, b * math.sin(alpha), 0.0],
        [a * math.cos(beta), b * math.cos(alpha), c],
    ]
    return out


def superimposition_matrix(v0: np.ndarray, v1: np.ndarray, scaling: bool = False,
                           usesvd: bool = True) -> np.ndarray:
    """The rigid motion (uniformly scaled when `scaling`) taking the points v0 (3xN or 4xN, N >= 3) closest to
    v1 in least squares. Kabsch's SVD when `usesvd`, else Horn's quaternion (the same optimum)."""
    a = np.array(v0, dtype=float)[:3]
    b = np.array(v1, dtype=float)[:3]
    if a.shape != b.shape or a.ndim != 2 or a.shape[1] < 3:
        raise ValueError("Vector sets are of wrong shape or type.")
    ca, cb = a.mean(axis=1), b.mean(axis=1)
    a, b = a - ca[:, None], b - cb[:, None]
    out = np.eye(4)
    if usesvd:
        u, _, vt = np.linalg.svd(b @ a.T)
        flip = np.diag([1.0, 1.0, float(np.sign(np.linalg.det(u @ vt)) or 1.0)])
        out[:3, :3] = u @ flip @ vt
    else:
        s = a @ b.T  # s[i, j] = sum of a_i * b_j
        trace = np.trace(s)
        k = np.empty((4, 4))
        k[0, 0] = trace
        k[0, 1:] = k[1:, 0] = [s[1, 2] - s[2, 1], s[2, 0] - s[0, 2], s[0, 1] - s[1, 0]]
        k[1:, 1:] = s + s.T - trace * np.eye(3)
        values, vectors = np.linalg.eigh(k)
        w, x, y, z = vectors[:, int(np.argmax(values))]
        out = quaternion_matrix([x, y, z, w])
    if scaling:
        out[:3, :3] *= math.sqrt(float(np.sum(b * b)) / float(np.sum(a * a)))
    out[:3, 3] = cb - out[:3, :3] @ ca
    return out


def random_vector(size: int | tuple[int, ...]) -> np.ndarray:
    """Uniform doubles in [0, 1)."""
    return np.random.random(size)


def random_quaternion(rand: Sequence[float] | None = None) -> np.ndarray:
    """A uniformly distributed unit quaternion [x, y, z, w] (Shoemake), from three uniform numbers in [0, 1)."""
    u = np.random.rand(3) if rand is None else np.asarray(rand, dtype=float)
    assert len(u) == 3
    low, high = math.sqrt(1.0 - u[0]), math.sqrt(u[0])
    first, second = 2.0 * math.pi * u[1], 2.0 * math.pi * u[2]
    return np.array([math.sin(first) * low, math.cos(first) * low, math.sin(second) * high,
                     math.cos(second) * high])


def random_rotation_matrix(rand: Sequence[float] | None = None) -> np.ndarray:
    """A uniformly distributed rotation as a 4x4 matrix."""
    return quaternion_matrix(random_quaternion(rand))


__all__ = [
    "clip_matrix",
    "compose_matrix",
    "decompose_matrix",
    "orthogonalization_matrix",
    "projection_from_matrix",
    "projection_matrix",
    "random_quaternion",
    "random_rotation_matrix",
    "random_vector",
    "reflection_from_matrix",
    "reflection_matrix",
    "rotation_from_matrix",
    "scale_from_matrix",
    "scale_matrix",
    "shear_from_matrix",
    "shear_matrix",
    "superimposition_matrix",
]
