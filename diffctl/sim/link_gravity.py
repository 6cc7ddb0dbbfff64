"""SDF `<gravity>false</gravity>` on a link: the world's gravity does not act on it (Gazebo's per-link switch).

PyBullet applies gravity to every body and has no per-link switch, so the weight of such links is cancelled
before every step by an equal and opposite force at their centre of mass (PyBullet clears applied forces
after each step). A PyBullet link merging several SDF links (fixed joints) cancels only the weight of those
that turn gravity off, at their own combined centre of mass. Models without such links cost nothing per step.
"""

from __future__ import annotations

from dataclasses import dataclass

import pybullet as pb

from diffctl.description.pose import Vec3
from diffctl.sim.entity import Entity


@dataclass(frozen=True)
class Counterweight:
    """The lift that cancels the weight of `mass_kg` at `com_link` (in the PyBullet link frame)."""

    body: int
    index: int  # PyBullet link index, -1 for the base
    mass_kg: float
    com_link: Vec3


def counterweights(entity: Entity) -> list[Counterweight]:
    """One per PyBullet link holding mass whose SDF link says `<gravity>false</gravity>` (none for static models)."""
    model = entity.model
    if model.static:
        return []
    sums: dict[tuple[int, int], tuple[float, Vec3]] = {}
    for link in model.links:
        if link.gravity or link.inertial is None or link.inertial.mass_kg <= 0.0:
            continue
        body, index, offset = entity.link_frame(link.name)
        m = link.inertial.mass_kg
        c = offset.compose(link.inertial.pose_link).xyz
        total, (x, y, z) = sums.get((body, index), (0.0, (0.0, 0.0, 0.0)))
        sums[(body, index)] = (total + m, (x + m * c[0], y + m * c[1], z + m * c[2]))
    return [
        Counterweight(body, index, total, (mx / total, my / total, mz / total))
        for (body, index), (total, (mx, my, mz)) in sums.items()
    ]


class GravityOff:
    """Cancels the weight of an entity's gravity-free links before each step."""

    def __init__(self, entity: Entity, gravity: Vec3) -> None:
        self.entity = entity
        self.weights = counterweights(entity)
        self._lifts = [
            (w, (-w.mass_kg * gravity[0], -w.mass_kg * gravity[1], -w.mass_kg * gravity[2])) for w in self.weights
        ]

    def before_step(self) -> None:
        cid = self.entity.client
        for w, lift in self._lifts:
            at = self.entity.pb_link_pose(w.body, w.index).transform_point(w.com_link)
            pb.applyExternalForce(w.body, w.index, lift, at, pb.WORLD_FRAME, physicsClientId=cid)
