"""Whether a link's mass and inertia are physically possible, by the rule sdformat applies (gz-math MassMatrix3).

sdformat reports "A link named X has invalid inertia" when `MassMatrix3::IsValid()` fails: the mass is negative,
the inertia matrix is not positive semi-definite, or its principal moments break the triangle inequality, each
within a tolerance of 10 machine epsilons of the largest possible moment. Zeros pass (a point mass, ixx 0 of a
rod), as do values no physics engine would simulate well; URDF (urdfdom) checks nothing at all.
"""

from __future__ import annotations

import sys

import numpy as np

TOLERANCE = 10.0  # gz-math's GZ_MASSMATRIX3_DEFAULT_TOLERANCE


def _epsilon(moments: tuple[float, float, float]) -> float:
    return TOLERANCE * sys.float_info.epsilon * 0.5 * abs(sum(moments))


def inertia_is_valid(mass_kg: float, ixx: float, ixy: float, ixz: float, iyy: float, iyz: float, izz: float) -> bool:
    """gz-math's `MassMatrix3::IsValid()` for these values."""
    moi = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]], dtype=float)
    eps = _epsilon((ixx, iyy, izz))
    near_positive = (
        mass_kg >= 0
        and ixx + eps >= 0
        and ixx * iyy - ixy * ixy + eps >= 0
        and float(np.linalg.det(moi)) + eps >= 0
    )
    if not near_positive:
        return False
    p = tuple(float(v) for v in np.linalg.eigvalsh(moi))
    eps = _epsilon((p[0], p[1], p[2]))
    return (
        all(v + eps >= 0 for v in p)
        and p[0] + p[1] + eps >= p[2]
        and p[1] + p[2] + eps >= p[0]
        and p[2] + p[0] + eps >= p[1]
    )
