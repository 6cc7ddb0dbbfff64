"""Turn a loaded SDF model into PyBullet multibody plans (pure: no physics client, testable on its own).

PyBullet's `loadSDF` cannot read Gazebo SDF (reference/sim_viz.md §1.1), so bodies are built from the
parsed model with `createMultiBody`. Planning rules:
- links joined by fixed joints merge into one PyBullet link (mass properties combined), unless their contact
  surfaces differ: PyBullet keeps one friction per link, so a frictionless caster stays a link of its own;
- likewise one SDF link whose collisions have different surfaces (a URDF caster lumped into base_link with its
  own <mu1>) is split: each further surface gets a PyBullet link on a fixed joint, appended after the others
  (indices of the rest unchanged), carrying a share of the mass at the same centre of mass with the same
  share of the inertia, so the sum is exactly the link's mass properties;
- a moving joint's frame becomes the child PyBullet link's frame (URDF semantics: joint frame = link frame),
  and every SDF link keeps an offset from the PyBullet link it ended up in, for sensors and poses;
- a static model becomes one massless PyBullet body; a joint to `world` pins the tree (a fixed one makes the
  base static, a moving one hangs the tree from a static anchor);
- each tree of links (links not connected by joints) becomes its own PyBullet body;
- a cylinder turning about its own axis (a wheel) meets the world as a contact disc and a core (wheel_contact.py);
- a wheel contact with a friction direction (`fdir1`) and next to no friction across it (mecanum and omni
  wheels: mu2 ~ 0) becomes a roller (mecanum_rollers.py);
- the collisions of a model's track links (TrackController's) that are fixed to each other ride on one belt link
  on joints along the tracks' x and y and about their z (plugins/track_belts.py);
- a shape with no volume (a size or radius <= 0, which SDF and URDF parsers accept) is left out, with a note;
- PyBullet takes at most 16 shapes per link (`MAX_COMPOUND_SHAPES`: createCollisionShapeArray and
  createVisualShapeArray silently keep the first 16, and a mesh past them crashes the process), and at most 127
  links per multibody (`MAX_LINKS`: createMultiBody silently drops the rest). A link with more shapes is split
  into links fixed to it (sharing its mass as a surface split does; static ones by surface too); a static model
  needing more links becomes several bodies; a moving tree still too large is refused, naming the model;
- principal moments of inertia are floored (`MIN_MOMENT_SHARE`): a zero one (sdformat accepts it) would make
  Bullet divide by zero about that axis.
A moving PyBullet link with no mass is an error: some link needs an <inertial>.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from diffctl.description.model import (
    Box,
    Capsule,
    Collision,
    Cylinder,
    Geometry,
    Joint,
    JointDynamics,
    JointLimits,
    Mesh,
    Model,
    Sphere,
    Surface,
    Visual,
)
from diffctl.description.pose import Pose, Quat, Vec3, quat_rotate
from diffctl.errors import DescriptionError
from diffctl.sim.inertia import MassProperties, combine, from_inertial, principal
from diffctl.sim.mecanum_rollers import ROLLER_MASS_SHARE, is_roller_surface, roller_frame
from diffctl.sim.plugins.system_names import system_kind
from diffctl.sim.plugins.track_math import track_orientation
from diffctl.sim.wheel_contact import rolls_about_own_axis, wheel_parts

DEFAULT_RGBA = (0.7, 0.7, 0.7, 1.0)


@dataclass(frozen=True)
class ShapeSpec:
    geometry: Geometry
    pose: Pose  # in the PyBullet link frame
    rgba: tuple[float, float, float, float] = DEFAULT_RGBA
    surface: Surface | None = None  # collisions only
    fdir1: Vec3 | None = None  # the surface's friction direction, in the PyBullet link frame


# The mass share each extra-surface PyBullet link takes from the link it was split from.
SURFACE_SPLIT_MASS_SHARE = 0.1
# The mass share a track's belt links take from the PyBullet link its track belongs to, and the part of it each
# of the two links carrying the belt (along x, then y) has.
BELT_MASS_SHARE = 0.05
BELT_CARRIAGE_SHARE = 0.1
_AXES: tuple[Vec3, Vec3, Vec3] = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
# PyBullet's fixed capacities (SharedMemoryPublic.h): shapes in one compound, links besides a body's base.
MAX_COMPOUND_SHAPES = 16
MAX_LINKS = 127


@dataclass(frozen=True)
class LinkPlan:
    """One PyBullet link (index -1 = the base) and the SDF links merged into it."""

    members: tuple[str, ...]  # SDF link names; members[0] names the PyBullet link ("" for a world anchor)
    frame_world: Pose  # the PyBullet link frame at spawn
    parent: int  # PyBullet index of the parent link (-1 = base); unused for the base
    joint: Joint | None  # the SDF joint that attaches it (None for the base)
    axis: Vec3  # joint axis in the PyBullet link frame
    mass_kg: float
    inertial_frame: Pose  # centre of mass and principal axes, in the PyBullet link frame
    inertia_diagonal: Vec3
    collisions: tuple[ShapeSpec, ...]
    visuals: tuple[ShapeSpec, ...]
    surface: Surface
    part_of: tuple[str, ...] = ()  # for a surface split: the SDF links whose collisions it carries
    # A roller (mecanum_rollers.py): (PyBullet index of the wheel it turns with, its speed ÷ the wheel's)
    gear: tuple[int, float] | None = None
    # a belt (track_belts.py): the SDF track links whose collisions it carries, each with their centre in its frame
    belt: tuple[tuple[str, Vec3], ...] = ()


@dataclass(frozen=True)
class BodyPlan:
    """One PyBullet multibody: links[0] is its base, links[i] is PyBullet link i-1."""

    links: tuple[LinkPlan, ...]

    @property
    def static_base(self) -> bool:
        return self.links[0].mass_kg == 0.0


@dataclass(frozen=True)
class LinkRef:
    """Where an SDF link lives: body number in the plan, PyBullet link index, pose in that link's frame."""

    body: int
    pb_link: int
    offset: Pose


@dataclass(frozen=True)
class ModelPlan:
    bodies: tuple[BodyPlan, ...]
    links: dict[str, LinkRef]
    joints: dict[str, tuple[int, int]]  # moving SDF joint → (body number, PyBullet joint index)
    notes: tuple[str, ...] = ()  # what of the model is left out of the physics, one line each


# A principal moment of inertia is at least this share of the link's largest (or MIN_MOMENT_KG_M2 when all
# are zero): Bullet inverts each one.
MIN_MOMENT_SHARE = 1e-6
MIN_MOMENT_KG_M2 = 1e-9


def degenerate(g: Geometry) -> str | None:
    """Why a shape has no volume to simulate, or None."""
    if isinstance(g, Box) and not all(v > 0 for v in g.size_m):
        return f"box size {' '.join(f'{v:g}' for v in g.size_m)}"
    if isinstance(g, Cylinder) and not (g.radius_m > 0 and g.length_m > 0):
        return f"cylinder radius {g.radius_m:g} length {g.length_m:g}"
    if isinstance(g, Capsule) and not (g.radius_m > 0 and g.length_m >= 0):
        return f"capsule radius {g.radius_m:g} length {g.length_m:g}"
    if isinstance(g, Sphere) and not g.radius_m > 0:
        return f"sphere radius {g.radius_m:g}"
    if isinstance(g, Mesh) and not g.path:
        return f"mesh {g.uri!r} holds no triangle"
    if isinstance(g, Mesh) and not all(v != 0 for v in g.scale):
        return f"mesh {g.uri!r} scaled {' '.join(f'{v:g}' for v in g.scale)}"
    return None


def plan_model(model: Model, *, split_colours: bool = False) -> ModelPlan:
    """The PyBullet bodies for `model` at the poses it was loaded (or spawned) with.

    `split_colours`: keep fixed links whose visuals differ in colour apart. PyBullet's OpenGL window draws a
    link in one colour (TinyRenderer honours each shape's), so the GUI trades a little speed for colours.
    """
    if not model.links:
        raise DescriptionError(f"model {model.name!r} has no <link>", source=model.source or None)
    return _Planner(model, split_colours).plan()


class _Planner:
    def __init__(self, model: Model, split_colours: bool = False) -> None:
        self.m = model
        self.split_colours = split_colours
        self.by_name = {link.name: link for link in model.links}
        self.children: dict[str, list[Joint]] = {link.name: [] for link in model.links}
        self.world_joint: dict[str, Joint] = {}
        child_of: set[str] = set()
        for j in model.joints:
            if j.parent == "world":
                self.world_joint[j.child] = j
                continue
            self.children[j.parent].append(j)
            child_of.add(j.child)
        self.roots = [link.name for link in model.links if link.name not in child_of]
        self.notes: list[str] = []
        # links whose contact is a moving belt (TrackController's <link>, track_belts.py)
        # (each with gz's <track_orientation>: the track runs along the x axis of the link's frame turned by it)
        self.tracks = {
            link: track_orientation(p, model.source)
            for p in model.plugins
            if system_kind(p.filename, p.name) == "track-controller"
            and (link := (p.get("link") or "").strip()) in self.by_name
        }

    def plan(self) -> ModelPlan:
        if self.m.static:
            return self._static()
        bodies: list[BodyPlan] = []
        refs: dict[str, LinkRef] = {}
        joints: dict[str, tuple[int, int]] = {}
        for root in self.roots:
            body_no = len(bodies)
            groups: list[dict] = []
            anchor = self.world_joint.get(root)
            if anchor is not None and anchor.type != "fixed":
                # A moving joint to the world: a massless static anchor at the joint frame carries the tree.
                groups.append(self._group([], anchor.pose_world, -1, None, static=True))
                groups.append(self._group([root], anchor.pose_world, -1, anchor))
            else:
                groups.append(self._group([root], self.by_name[root].pose_world, -1, None, static=anchor is not None))
            self._grow(groups, len(groups) - 1, root)
            finished = _split_belts(_split_rollers(tuple(self._finish(g) for g in groups)), groups)
            links = _split_shape_count(_split_surfaces(finished))
            if len(links) > MAX_LINKS + 1:
                raise DescriptionError(
                    f"model {self.m.name!r}: the tree rooted at link {root!r} needs {len(links) - 1} PyBullet "
                    f"links besides its base, more than the {MAX_LINKS} one PyBullet body holds",
                    source=self.m.source or None,
                    field=f"model {self.m.name}",
                    hint="merge links with fixed joints, give links fewer collisions and visuals (16 fit in one "
                    "link), or make the model <static>",
                )
            links, renumbered = _pybullet_order(links)
            bodies.append(BodyPlan(links))
            for pb_index, g in enumerate(groups, start=-1):
                index = renumbered[pb_index]
                for name in g["members"]:
                    refs[name] = LinkRef(body_no, index, g["frame"].inverse().compose(self.by_name[name].pose_world))
                if g["joint"] is not None and g["joint"].type != "fixed":
                    joints[g["joint"].name] = (body_no, index)
        return ModelPlan(tuple(bodies), refs, joints, tuple(self.notes))

    def _static(self) -> ModelPlan:
        base = self.by_name[self.m.root_link()]
        g = self._group([link.name for link in self.m.links], base.pose_world, -1, None, static=True)
        refs = {n: LinkRef(0, -1, g["frame"].inverse().compose(self.by_name[n].pose_world)) for n in g["members"]}
        chunks = _split_shape_count((self._finish(g),), by_surface=True)
        # Nothing moves: more chunks than one body holds simply make more bodies, each a static base.
        bodies = []
        for start in range(0, len(chunks), MAX_LINKS + 1):
            part = chunks[start : start + MAX_LINKS + 1]
            bodies.append(BodyPlan(tuple(dataclasses.replace(lp, parent=-1) for lp in part)))
        return ModelPlan(tuple(bodies), refs, {}, tuple(self.notes))

    @staticmethod
    def _group(members: list[str], frame: Pose, parent: int, joint: Joint | None, static: bool = False) -> dict:
        return {"members": members, "frame": frame, "parent": parent, "joint": joint, "static": static}

    def _grow(self, groups: list[dict], gi: int, link_name: str) -> None:
        for j in self.children[link_name]:
            child = j.child
            if j.type == "fixed" and self._same_surface(groups[gi], child) and self._same_colour(groups[gi], child):
                groups[gi]["members"].append(child)
                self._grow(groups, gi, child)
            else:
                # A fixed joint that cannot merge still keeps the child's own frame (no joint pose to honour).
                frame = j.pose_world if j.type != "fixed" else self.by_name[child].pose_world
                groups.append(self._group([child], frame, gi - 1, j))
                self._grow(groups, len(groups) - 1, child)

    def _surfaces(self, names: list[str]) -> set[Surface]:
        return {c.surface for n in names for c in self.by_name[n].collisions}

    def _same_surface(self, group: dict, child: str) -> bool:
        mine, theirs = self._surfaces(group["members"]), self._surfaces([child])
        return not mine or not theirs or mine == theirs

    def _same_colour(self, group: dict, child: str) -> bool:
        if not self.split_colours:
            return True
        mine = {v.rgba for n in group["members"] for v in self.by_name[n].visuals}
        theirs = {v.rgba for v in self.by_name[child].visuals}
        return not mine or not theirs or mine == theirs

    def _finish(self, g: dict) -> LinkPlan:
        frame: Pose = g["frame"]
        inv = frame.inverse()
        parts: list[MassProperties] = []
        collisions: list[ShapeSpec] = []
        visuals: list[ShapeSpec] = []
        surfaces: list[Surface] = []
        for name in g["members"]:
            link = self.by_name[name]
            in_frame = inv.compose(link.pose_world)
            if link.inertial is not None:
                parts.append(from_inertial(link.inertial, in_frame))
            for kind, shapes in (("collision", link.collisions), ("visual", link.visuals)):
                for c in shapes:
                    why = degenerate(c.geometry)
                    if why is not None:
                        self.notes.append(f"{kind} {c.name!r} of link {name!r} has no volume ({why}): left out")
                    elif isinstance(c, Collision) and name in self.tracks and not g["static"]:
                        g.setdefault("belts", {}).setdefault(name, []).append(_shape(c, in_frame))
                        g.setdefault("track_axes", {})[name] = tuple(
                            in_frame.rotate(self.tracks[name].rotate(axis)) for axis in _AXES
                        )
                    elif isinstance(c, Collision):
                        collisions.append(_shape(c, in_frame))
                        surfaces.append(c.surface)
                    else:
                        visuals.append(_shape(c, in_frame))
        mp = combine(parts)
        joint: Joint | None = g["joint"]
        if g["static"]:
            mass, inertial_frame, diag = 0.0, Pose(), (0.0, 0.0, 0.0)
        elif mp.mass_kg <= 0.0:
            names = ", ".join(repr(n) for n in g["members"]) or "(anchor)"
            raise DescriptionError(
                f"link {names} of model {self.m.name!r} moves but has no mass",
                source=self.m.source or None,
                field=f"model {self.m.name}: link {g['members'][0] if g['members'] else ''}",
                hint="add an <inertial> with <mass> and <inertia>, or fix it to a link that has one",
            )
        else:
            mass = mp.mass_kg
            inertial_frame, diag = principal(mp)
            floor = max(MIN_MOMENT_KG_M2, MIN_MOMENT_SHARE * max(diag))
            if min(diag) < floor:
                diag = (max(diag[0], floor), max(diag[1], floor), max(diag[2], floor))
        if joint is not None and (joint.dynamics.damping < 0 or joint.dynamics.friction < 0):
            d = joint.dynamics
            self.notes.append(
                f"joint {joint.name!r}: negative <dynamics> (damping {d.damping:g}, friction {d.friction:g}) "
                "simulated as 0"
            )
        if joint is not None and joint.type in ("revolute", "prismatic") and joint.limits.lower > joint.limits.upper:
            self.notes.append(
                f"joint {joint.name!r}: <lower> {joint.limits.lower:g} is above <upper> {joint.limits.upper:g}: "
                "no position limit simulated"
            )
        axis: Vec3 = (0.0, 0.0, 1.0)
        if joint is not None and joint.axis_world is not None:
            axis = frame.inverse().rotate(joint.axis_world)
            if joint.type in ("revolute", "continuous"):
                collisions = _wheel_contacts(collisions, axis)
        return LinkPlan(
            members=tuple(g["members"]),
            frame_world=frame,
            parent=g["parent"],
            joint=joint,
            axis=axis,
            mass_kg=mass,
            inertial_frame=inertial_frame,
            inertia_diagonal=diag,
            collisions=tuple(collisions),
            visuals=tuple(visuals),
            surface=surfaces[0] if surfaces else Surface(),
        )


def _shape(element: Collision | Visual, link_in_frame: Pose) -> ShapeSpec:
    rgba = getattr(element, "rgba", None) or DEFAULT_RGBA
    surface = element.surface if isinstance(element, Collision) else None
    fdir1 = link_in_frame.rotate(surface.fdir1) if surface is not None and surface.fdir1 is not None else None
    return ShapeSpec(element.geometry, link_in_frame.compose(element.pose_link), rgba, surface, fdir1)


def _wheel_contacts(collisions: list[ShapeSpec], axis: Vec3) -> list[ShapeSpec]:
    """Each cylinder turning about its own axis as a contact disc and a core (see wheel_contact.py)."""
    out: list[ShapeSpec] = []
    for c in collisions:
        if c.surface is not None and is_roller_surface(c.surface):
            out.append(c)  # a roller meets the ground as a sphere of its own (mecanum_rollers.py)
            continue
        parts = wheel_parts(c.geometry) if isinstance(c.geometry, Cylinder) else None
        if parts is None or not rolls_about_own_axis(c.pose, axis):
            out.append(c)
            continue
        out.extend(ShapeSpec(g, c.pose, c.rgba, c.surface) for g in parts)
    return out


def _pybullet_order(links: tuple[LinkPlan, ...]) -> tuple[tuple[LinkPlan, ...], dict[int, int]]:
    """The links in the order createMultiBody numbers them, whatever order they are given in: depth first, each
    link's children (in the order given) right after it. The splits above append links to parents anywhere in
    the tree, which PyBullet would renumber behind our back. Also each old PyBullet index's new one."""
    children: dict[int, list[int]] = {}
    for i, lp in enumerate(links[1:]):
        children.setdefault(lp.parent, []).append(i)
    order: list[int] = []
    pending = list(reversed(children.get(-1, [])))
    while pending:
        i = pending.pop()
        order.append(i)
        pending.extend(reversed(children.get(i, [])))
    new = {old: k for k, old in enumerate(order)} | {-1: -1}
    if order == list(range(len(order))):
        return links, new
    moved = [
        dataclasses.replace(
            links[old + 1],
            parent=new[links[old + 1].parent],
            gear=None if links[old + 1].gear is None else (new[links[old + 1].gear[0]], links[old + 1].gear[1]),
        )
        for old in order
    ]
    return (links[0], *moved), new


def _split_surfaces(links: tuple[LinkPlan, ...]) -> tuple[LinkPlan, ...]:
    """Each moving PyBullet link whose collisions have several surfaces keeps its first surface's shapes; the
    others move to new links fixed to it (appended), sharing its mass properties exactly."""
    out = list(links)
    extra: list[LinkPlan] = []
    for i, lp in enumerate(links):
        by_surface: dict[Surface, list[ShapeSpec]] = {}
        for c in lp.collisions:
            by_surface.setdefault(c.surface or lp.surface, []).append(c)
        if len(by_surface) < 2 or lp.mass_kg <= 0.0:
            continue  # a static body has no mass to share: it keeps its first surface
        parts = list(by_surface.items())
        share = min(SURFACE_SPLIT_MASS_SHARE, 0.5 / (len(parts) - 1))
        keep = 1.0 - share * (len(parts) - 1)
        for surface, shapes in parts[1:]:
            extra.append(
                LinkPlan(
                    members=(),
                    frame_world=lp.frame_world,
                    parent=i - 1,
                    joint=None,
                    axis=(0.0, 0.0, 1.0),
                    mass_kg=lp.mass_kg * share,
                    inertial_frame=lp.inertial_frame,
                    inertia_diagonal=_scaled(lp.inertia_diagonal, share),
                    collisions=tuple(shapes),
                    visuals=(),
                    surface=surface,
                    part_of=lp.members or lp.part_of,
                )
            )
        first_surface, first_shapes = parts[0]
        # (a belt keeps being one: its other surfaces ride on it)
        out[i] = dataclasses.replace(
            lp,
            mass_kg=lp.mass_kg * keep,
            inertia_diagonal=_scaled(lp.inertia_diagonal, keep),
            collisions=tuple(first_shapes),
            surface=first_surface,
        )
    return (*out, *extra)


def _split_belts(links: tuple[LinkPlan, ...], groups: list[dict]) -> tuple[LinkPlan, ...]:
    """The collisions of tracks rigidly joined to each other (fixed joints, the same track plane) move to one belt
    link that can slide along the tracks' x and y and turn about their z relative to the PyBullet link they are
    fixed to (three joints in a chain: PyBullet has no planar joint), appended; each track's link gives the belt
    a share of its mass (track_belts.py drives it). One belt for a vehicle's tracks keeps the degrees of freedom,
    which the solver pays for on every contact, at three."""
    out = list(links)
    shared: dict[tuple, list[int]] = {}
    for i, g in enumerate(groups):  # (links may hold rollers past the groups)
        if g.get("belts") and links[i].mass_kg > 0.0:
            root = _rigid_root(groups, links, i)
            frame = groups[root]["frame"].inverse().compose(groups[i]["frame"])
            axes = next(iter(g["track_axes"].values()))
            plane = tuple(round(v, 6) for a in axes[:2] for v in frame.rotate(a))
            shared.setdefault((root, plane), []).append(i)
    extra: list[LinkPlan] = []
    for (root, _), members in shared.items():
        root_frame: Pose = groups[root]["frame"]
        shapes: list[ShapeSpec] = []
        centres: list[tuple[str, Vec3]] = []
        parts: list[MassProperties] = []
        for i in members:
            lp, belts = links[i], groups[i]["belts"]
            in_root = root_frame.inverse().compose(groups[i]["frame"])
            share = min(BELT_MASS_SHARE, 0.5 / len(belts))
            keep = 1.0 - share * len(belts)
            out[i] = dataclasses.replace(
                lp, mass_kg=lp.mass_kg * keep, inertia_diagonal=_scaled(lp.inertia_diagonal, keep)
            )
            com = in_root.compose(lp.inertial_frame)
            tensor = _tensor(com.quat, _scaled(lp.inertia_diagonal, share))
            parts.extend(MassProperties(lp.mass_kg * share, com.xyz, tensor) for _ in belts)
            for name, track_shapes in belts.items():
                moved = [dataclasses.replace(c, pose=in_root.compose(c.pose)) for c in track_shapes]
                shapes.extend(moved)
                n = len(moved)
                centres.append((name, tuple(sum(c.pose.xyz[k] for c in moved) / n for k in range(3))))  # type: ignore[misc]
        axes = tuple(
            root_frame.inverse().compose(groups[members[0]]["frame"]).rotate(a)
            for a in next(iter(groups[members[0]]["track_axes"].values()))
        )
        mp = combine(parts)
        inertial_frame, diag = principal(mp)
        surface = shapes[0].surface or links[members[0]].surface
        names = tuple(name for name, _ in centres)
        parent = root - 1
        chain = (("x", "prismatic", axes[0]), ("y", "prismatic", axes[1]), ("", "revolute", axes[2]))
        for suffix, kind, axis in chain:
            last = not suffix
            joint = Joint(
                name=f"{names[0]}::belt{'_' + suffix if suffix else ''}",
                type=kind,
                parent=names[0],
                child=names[0],
                pose_world=root_frame,
                pose_child=Pose(),
                axis_world=root_frame.rotate(axis),
                axis_child=axis,
            )
            # the belt itself takes most of the mass: the two links of the chain only carry it
            part = BELT_CARRIAGE_SHARE if not last else 1.0 - 2 * BELT_CARRIAGE_SHARE
            extra.append(
                LinkPlan(
                    members=(),
                    frame_world=root_frame,
                    parent=parent,
                    joint=joint,
                    axis=axis,
                    mass_kg=mp.mass_kg * part,
                    inertial_frame=inertial_frame,
                    inertia_diagonal=_scaled(diag, part),
                    collisions=tuple(shapes) if last else (),
                    visuals=(),
                    surface=surface,
                    part_of=names,
                    belt=tuple(centres) if last else (),
                )
            )
            parent = len(out) + len(extra) - 2  # the PyBullet index of the link just appended
    return (*out, *extra)


def _rigid_root(groups: list[dict], links: tuple[LinkPlan, ...], i: int) -> int:
    """The group that group `i` is fixed to through fixed joints only, as far up as has mass."""
    while True:
        joint = groups[i]["joint"]
        if joint is None or joint.type != "fixed":
            return i
        parent = groups[i]["parent"] + 1
        if links[parent].mass_kg <= 0.0:
            return i
        i = parent


def _tensor(q: Quat, diagonal: Vec3) -> tuple[Vec3, Vec3, Vec3]:
    """The inertia tensor of principal moments `diagonal` along the axes of rotation `q`."""
    cols = [quat_rotate(q, axis) for axis in ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))]
    rows = [tuple(sum(cols[k][r] * diagonal[k] * cols[k][c] for k in range(3)) for c in range(3)) for r in range(3)]
    return (rows[0], rows[1], rows[2])  # type: ignore[return-value]


def _split_rollers(links: tuple[LinkPlan, ...]) -> tuple[LinkPlan, ...]:
    """Each wheel contact that grips along one direction only moves to a roller link hung from the wheel's
    parent and geared to the wheel (appended; see mecanum_rollers.py), with a share of the wheel's mass."""
    out = list(links)
    extra: list[LinkPlan] = []
    for i, lp in enumerate(links):
        joint = lp.joint
        if joint is None or joint.type not in ("revolute", "continuous") or lp.mass_kg <= 0.0:
            continue
        axis_world = lp.frame_world.rotate(lp.axis)
        keep: list[ShapeSpec] = []
        rollers: list[tuple[ShapeSpec, Pose, float]] = []
        for c in lp.collisions:
            s, g = c.surface, c.geometry
            if s is None or c.fdir1 is None or not is_roller_surface(s) or not isinstance(g, (Sphere, Cylinder)):
                keep.append(c)
                continue
            center = lp.frame_world.compose(c.pose).xyz
            frame = roller_frame(center, lp.frame_world.rotate(c.fdir1), axis_world, s.mu >= s.mu2)
            if frame is None:
                keep.append(c)
            else:
                rollers.append((c, *frame))
        if not rollers:
            continue
        share = min(ROLLER_MASS_SHARE, 0.5 / len(rollers))
        keep_share = 1.0 - share * len(rollers)
        out[i] = dataclasses.replace(
            lp,
            collisions=tuple(keep),
            mass_kg=lp.mass_kg * keep_share,
            inertia_diagonal=_scaled(lp.inertia_diagonal, keep_share),
        )
        for c, frame, ratio in rollers:
            s = c.surface or lp.surface
            radius = c.geometry.radius_m  # type: ignore[union-attr]
            grip = Surface(max(s.mu, s.mu2), 0.0, s.restitution)
            extra.append(
                LinkPlan(
                    members=(),
                    frame_world=frame,
                    parent=lp.parent,
                    joint=dataclasses.replace(
                        joint,
                        name=f"{joint.name}::roller",
                        type="continuous",
                        limits=JointLimits(),
                        dynamics=JointDynamics(),
                        mimic=None,
                    ),
                    axis=(1.0, 0.0, 0.0),
                    mass_kg=lp.mass_kg * share,
                    inertial_frame=Pose(),
                    inertia_diagonal=(max(lp.inertia_diagonal) * share,) * 3,
                    collisions=(ShapeSpec(Sphere(radius), Pose(), c.rgba, grip),),
                    visuals=(),
                    surface=grip,
                    part_of=lp.members or lp.part_of,
                    gear=(i - 1, ratio),
                )
            )
    return (*out, *extra)


def _split_shape_count(links: tuple[LinkPlan, ...], *, by_surface: bool = False) -> tuple[LinkPlan, ...]:
    """Each link with more than MAX_COMPOUND_SHAPES collisions or visuals keeps the first of each; the others
    move to new links fixed to it (appended), sharing its mass properties exactly. `by_surface`: collisions of
    different surfaces go to different links as well (a static body, which has no mass to share by surface)."""
    out = list(links)
    extra: list[LinkPlan] = []
    n = MAX_COMPOUND_SHAPES
    for i, lp in enumerate(links):
        groups: dict[Surface, list[ShapeSpec]] = {}
        for c in lp.collisions:
            groups.setdefault((c.surface or lp.surface) if by_surface else lp.surface, []).append(c)
        collision_chunks = [(sf, tuple(sh[k : k + n])) for sf, sh in groups.items() for k in range(0, len(sh), n)]
        visual_chunks = [lp.visuals[k : k + n] for k in range(0, len(lp.visuals), n)]
        count = max(len(collision_chunks), len(visual_chunks), 1)
        if count == 1:
            continue
        share = 0.0 if lp.mass_kg <= 0.0 else min(SURFACE_SPLIT_MASS_SHARE, 0.5 / (count - 1))
        keep = 1.0 - share * (count - 1)

        chunks = [
            (
                collision_chunks[k][1] if k < len(collision_chunks) else (),
                visual_chunks[k] if k < len(visual_chunks) else (),
                collision_chunks[k][0] if k < len(collision_chunks) else lp.surface,
            )
            for k in range(count)
        ]
        shapes, visuals, surface = chunks[0]
        out[i] = dataclasses.replace(
            lp,
            mass_kg=lp.mass_kg * keep,
            inertia_diagonal=_scaled(lp.inertia_diagonal, keep),
            collisions=shapes,
            visuals=visuals,
            surface=surface,
        )
        for shapes, visuals, surface in chunks[1:]:
            extra.append(
                LinkPlan(
                    members=(),
                    frame_world=lp.frame_world,
                    parent=i - 1,
                    joint=None,
                    axis=(0.0, 0.0, 1.0),
                    mass_kg=lp.mass_kg * share,
                    inertial_frame=lp.inertial_frame,
                    inertia_diagonal=_scaled(lp.inertia_diagonal, share),
                    collisions=shapes,
                    visuals=visuals,
                    surface=surface,
                    part_of=lp.members or lp.part_of,
                )
            )
    return (*out, *extra)


def _scaled(v: Vec3, k: float) -> Vec3:
    return (v[0] * k, v[1] * k, v[2] * k)
