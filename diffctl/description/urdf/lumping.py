"""Mass properties of links merged by fixed-joint lumping: pure math, no XML.

sdformat's `ReduceInertialToParent` moves the child's inertia into the parent link frame (rotate, then the
parallel-axis shift), adds the two about the combined centre of mass, and expresses the result in the parent's
own inertial-frame orientation (identity when the parent had no `<inertial>`). The same result is computed here
with 3×3 matrices instead of ODE's dMass helpers.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from diffctl.description.pose import Pose

Inertia6 = tuple[float, float, float, float, float, float]  # ixx ixy ixz iyy iyz izz


@dataclass(frozen=True)
class MassProperties:
    mass_kg: float
    frame: Pose  # centre of mass (position) and the inertia tensor's axes (orientation), in the link frame
    inertia_kg_m2: Inertia6  # about the centre of mass, in `frame`'s axes


def tensor(i: Inertia6) -> np.ndarray:
    ixx, ixy, ixz, iyy, iyz, izz = i
    return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]], dtype=float)


def components(m: np.ndarray) -> Inertia6:
    # Average the off-diagonals so rounding never makes the tensor asymmetric.
    sym = (m + m.T) / 2.0
    return (
        float(sym[0, 0]),
        float(sym[0, 1]),
        float(sym[0, 2]),
        float(sym[1, 1]),
        float(sym[1, 2]),
        float(sym[2, 2]),
    )


def _rotation(p: Pose) -> np.ndarray:
    return np.array(p.to_matrix(), dtype=float)[:3, :3]


def inertia_in_link_axes(props: MassProperties) -> np.ndarray:
    """The tensor about the centre of mass, expressed in the link frame's axes: R I Rᵀ."""
    r = _rotation(props.frame)
    return r @ tensor(props.inertia_kg_m2) @ r.T


def point_mass_shift(mass_kg: float, offset_m: np.ndarray) -> np.ndarray:
    """Parallel-axis term m (|d|² E − d dᵀ) for moving the reference point by `offset_m` from the centre of mass."""
    d = np.asarray(offset_m, dtype=float)
    return mass_kg * (float(d @ d) * np.eye(3) - np.outer(d, d))


def merge(parent: MassProperties | None, child: MassProperties, child_in_parent: Pose) -> MassProperties:
    """The parent link's mass properties after the child link (at `child_in_parent`) is welded onto it."""
    base = parent if parent is not None else MassProperties(0.0, Pose(), (0.0,) * 6)  # type: ignore[arg-type]
    child_frame = child_in_parent.compose(child.frame)
    moved = MassProperties(child.mass_kg, child_frame, child.inertia_kg_m2)
    total = base.mass_kg + moved.mass_kg
    c_parent = np.array(base.frame.xyz)
    c_child = np.array(moved.frame.xyz)
    if total <= 0.0:
        # Two massless bodies: sdformat would divide by zero here; keep the parent's frame and no mass.
        return MassProperties(0.0, base.frame, (0.0,) * 6)  # type: ignore[arg-type]
    com = (base.mass_kg * c_parent + moved.mass_kg * c_child) / total
    about_com = (
        inertia_in_link_axes(base)
        + point_mass_shift(base.mass_kg, c_parent - com)
        + inertia_in_link_axes(moved)
        + point_mass_shift(moved.mass_kg, c_child - com)
    )
    r = _rotation(base.frame)
    frame = Pose((float(com[0]), float(com[1]), float(com[2])), base.frame.quat)
    return MassProperties(total, frame, components(r.T @ about_com @ r))
