"""Mass properties of rigidly joined links: combine SDF inertials and find their principal axes (pure math).

Links joined by fixed joints become one PyBullet link (fewer bodies, faster steps), so their inertials are
summed with the parallel-axis theorem; PyBullet then takes the centre of mass, the principal axes as the
inertial frame orientation, and the principal moments as `localInertiaDiagonal`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from diffctl.description.model import Inertial
from diffctl.description.pose import Pose, Quat, Vec3, quat_from_matrix, quat_to_matrix

# Bullet misbehaves with exactly zero principal moments (point masses): floor them far below any real part.
MIN_MOMENT_KG_M2 = 1e-12


@dataclass(frozen=True)
class MassProperties:
    """Mass, centre of mass and inertia tensor about the centre of mass, in one reference frame's axes."""

    mass_kg: float
    com_m: Vec3
    tensor_kg_m2: tuple[Vec3, Vec3, Vec3]

    @staticmethod
    def zero() -> MassProperties:
        return MassProperties(0.0, (0.0, 0.0, 0.0), ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)))


def from_inertial(inertial: Inertial, link_in_frame: Pose) -> MassProperties:
    """An SDF inertial (given in its link's frame) expressed in a frame where the link sits at `link_in_frame`."""
    com_pose = link_in_frame.compose(inertial.pose_link)
    r = np.array(quat_to_matrix(com_pose.quat))
    i_local = np.array(
        [
            [inertial.ixx, inertial.ixy, inertial.ixz],
            [inertial.ixy, inertial.iyy, inertial.iyz],
            [inertial.ixz, inertial.iyz, inertial.izz],
        ]
    )
    t = r @ i_local @ r.T
    return MassProperties(inertial.mass_kg, com_pose.xyz, _tuple3(t))


def combine(parts: list[MassProperties]) -> MassProperties:
    """The mass properties of several parts rigidly joined (all given in the same frame)."""
    parts = [p for p in parts if p.mass_kg > 0.0]
    if not parts:
        return MassProperties.zero()
    total = sum(p.mass_kg for p in parts)
    com = sum(np.array(p.com_m) * p.mass_kg for p in parts) / total
    t = np.zeros((3, 3))
    for p in parts:
        d = np.array(p.com_m) - com
        # Parallel-axis theorem: I_c + m (|d|² E − d dᵀ)
        t += np.array(p.tensor_kg_m2) + p.mass_kg * (float(d @ d) * np.eye(3) - np.outer(d, d))
    return MassProperties(total, (float(com[0]), float(com[1]), float(com[2])), _tuple3(t))


def principal(mp: MassProperties) -> tuple[Pose, Vec3]:
    """(inertial frame: centre of mass + principal axes orientation, principal moments) of `mp`."""
    t = np.array(mp.tensor_kg_m2)
    off_diagonal = abs(t[0, 1]) + abs(t[0, 2]) + abs(t[1, 2])
    if off_diagonal <= 1e-15 * max(1.0, float(np.abs(np.diag(t)).max())):
        # Already principal: keep the axes as written, so a plain SDF inertia stays exactly as given.
        q: Quat = (0.0, 0.0, 0.0, 1.0)
        moments = np.diag(t)
    else:
        moments, vectors = np.linalg.eigh(t)
        if np.linalg.det(vectors) < 0:
            vectors[:, 2] = -vectors[:, 2]
        q = quat_from_matrix(vectors.tolist())
    diag = tuple(max(float(m), MIN_MOMENT_KG_M2) for m in moments)
    return Pose(mp.com_m, q), (diag[0], diag[1], diag[2])


def _tuple3(m: np.ndarray) -> tuple[Vec3, Vec3, Vec3]:
    rows = [(float(r[0]), float(r[1]), float(r[2])) for r in m]
    return (rows[0], rows[1], rows[2])
