"""SDF `<self_collide>` in PyBullet terms (pure: which bodies get self-collision, which link pairs are filtered out).

SDF (link.sdf): two links of one model collide if either has `<self_collide>` (the model's `<self_collide>` sets
it for every link); links connected by a joint never collide. PyBullet lets no two links of one multibody
collide unless the body is built with URDF_USE_SELF_COLLISION, which then excludes exactly the parent–child
pairs (measured: a grandparent still collides), so the joint rule comes for free; pairs where neither link
self-collides are filtered out one by one. Separate trees of one model are separate PyBullet bodies, which
PyBullet lets collide by default: their pairs follow the same rule. A PyBullet link that merges several SDF
links (fixed joints) self-collides when any of them does. A link split off another (a surface, a track's belt,
a mecanum roller: body_plan.py) is not its PyBullet link's child, or not its only one: PyBullet's rule misses
the pairs that carry one SDF link, or two joined ones, which are filtered out as well.
"""

from __future__ import annotations

import itertools

import pybullet as pb

from diffctl.description.model import Model
from diffctl.sim.body_plan import ModelPlan

# One PyBullet link: (body number in the plan, PyBullet link index, -1 = base).
PbLink = tuple[int, int]


def _colliding_links(model: Model, plan: ModelPlan) -> dict[PbLink, tuple[bool, frozenset[str]]]:
    """Every PyBullet link of the model that has collision shapes: whether it self-collides, and the SDF links
    it carries."""
    wants = {link.name: model.self_collide or link.self_collide for link in model.links}
    out: dict[PbLink, tuple[bool, frozenset[str]]] = {}
    for body_no, body in enumerate(plan.bodies):
        for index, lp in enumerate(body.links, start=-1):
            if lp.collisions:
                names = frozenset(lp.members or lp.part_of)
                out[(body_no, index)] = (any(wants[name] for name in names), names)
    return out


def _kept_apart(a: frozenset[str], b: frozenset[str], joined: set[frozenset[str]]) -> bool:
    """Whether SDF keeps links carrying these SDF links apart: one link, or two a joint connects."""
    return bool(a & b) or any(frozenset((x, y)) in joined for x in a for y in b)


def body_flags(model: Model, plan: ModelPlan) -> list[int]:
    """createMultiBody flags per body: self-collision on where some pair of its links should collide."""
    if model.static:
        return [0] * len(plan.bodies)
    links = _colliding_links(model, plan)
    flags = []
    for body_no in range(len(plan.bodies)):
        mine = [wants for (b, _), (wants, _) in links.items() if b == body_no]
        flags.append(pb.URDF_USE_SELF_COLLISION if len(mine) > 1 and any(mine) else 0)
    return flags


def filtered_pairs(model: Model, plan: ModelPlan) -> list[tuple[PbLink, PbLink]]:
    """Pairs of PyBullet links of this model that PyBullet would let collide and SDF does not."""
    if model.static:
        return []
    flags = body_flags(model, plan)
    links = _colliding_links(model, plan)
    joined = {frozenset((j.parent, j.child)) for j in model.joints}
    pairs = []
    for (a, (wants_a, names_a)), (b, (wants_b, names_b)) in itertools.combinations(links.items(), 2):
        if (wants_a or wants_b) and not _kept_apart(names_a, names_b, joined):
            continue
        same_body = a[0] == b[0]
        if same_body and not flags[a[0]]:
            continue  # PyBullet already keeps the links of a body without self-collision apart
        pairs.append((a, b))
    return pairs


def apply(client: int, model: Model, plan: ModelPlan, bodies: tuple[int, ...]) -> None:
    """Filter out the pairs SDF does not let collide (the bodies were built with `body_flags`)."""
    for (body_a, link_a), (body_b, link_b) in filtered_pairs(model, plan):
        pb.setCollisionFilterPair(bodies[body_a], bodies[body_b], link_a, link_b, 0, physicsClientId=client)
