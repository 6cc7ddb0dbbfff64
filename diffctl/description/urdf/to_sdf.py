"""A `UrdfRobot` as the SDF `<model>` Gazebo makes of it (sdformat's parser_urdf), as an lxml element tree.

Simulation view (`lump=True`, what gz-sim spawns): fixed joints are reduced — the child's mass is merged into
the parent (`lumping.merge`), its visuals and collisions move to the parent under sdformat's names
(`<parent>_fixed_joint_lump__<child>_visual_1`), the child link and its joint survive as model `<frame>`s, and
`<gazebo reference>` extensions follow. `<preserveFixedJoint>` keeps a fixed joint, the legacy
`<disableFixedJointLumping>` keeps it as a revolute joint locked at 0. A link left without mass is dropped with
its subtree ("not modeled in sdf"), `continuous` becomes an unlimited `revolute`, `floating`/`planar` joints
make no joint.

Kinematic view (`lump=False`, what robot_state_publisher and the visualizer read): every URDF link and joint as
written, massless links included, so TF has every frame ROS would publish.

Every generated element carries the URDF line it came from, so errors raised while building the Model point
into the user's file.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from pathlib import Path

from lxml import etree

from diffctl.description.missing_mesh import MeshNotFound, report_missing_mesh
from diffctl.description.pose import Pose
from diffctl.description.urdf.gazebo_ext import (
    GazeboExtension,
    apply_to_collision,
    apply_to_joint,
    apply_to_link,
    apply_to_model,
    apply_to_visual,
    read_extensions,
)
from diffctl.description.urdf.lumping import MassProperties, merge
from diffctl.description.urdf.meshes import resolve_mesh
from diffctl.description.urdf.parse import UrdfGeometry, UrdfJoint, UrdfRobot, UrdfShape
from diffctl.errors import DescriptionError

Element = etree._Element
LUMP_PREFIX = "_fixed_joint_lump__"
SDF_VERSION = "1.11"


@dataclass(frozen=True)
class ConversionOptions:
    lump: bool = True  # Gazebo's simulation view; False keeps every link and joint (the kinematic view)
    resolve_meshes: bool = True  # find mesh files now (a missing one is an error)
    base_dir: Path = field(default_factory=Path.cwd)  # relative mesh paths resolve here


@dataclass
class _Body:
    """A link that becomes an SDF <link>, with everything lumped into it."""

    name: str
    mass: MassProperties | None
    visuals: list[tuple[UrdfShape, Pose, str]] = field(default_factory=list)  # shape, pose in body, name
    collisions: list[tuple[UrdfShape, Pose, str]] = field(default_factory=list)


def _num(v: float) -> str:
    return "0" if v == 0 else repr(float(v))


def _pose_text(p: Pose) -> str:
    return " ".join(_num(v) for v in (*p.xyz, *p.rpy))


def _sub(parent: Element, tag: str, text: str | None = None, line: int = 0, **attrs: str) -> Element:
    el = etree.SubElement(parent, tag, **attrs)
    if text is not None:
        el.text = text
    if line:
        el.sourceline = line
    return el


class _Converter:
    def __init__(self, robot: UrdfRobot, options: ConversionOptions) -> None:
        self.robot = robot
        self.options = options
        self.ignored: list[str] = []
        self.mesh_uris: dict[tuple[str, str, int], str] = {}  # (link, visual|collision, index) → URDF's URI
        self.extensions = read_extensions(robot.gazebo, robot.source)
        self.preserve: set[str] = set()
        self.locked: set[str] = set()  # disableFixedJointLumping: kept as a revolute joint with limits 0/0
        for ext in self.extensions:
            if ext.reference in robot.joints and robot.joints[ext.reference].type == "fixed":
                if ext.flag("preserveFixedJoint"):
                    self.preserve.add(ext.reference)
                elif ext.flag("disableFixedJointLumping"):
                    self.locked.add(ext.reference)
        self.locked -= self.preserve  # both given: preserve wins

    # --- which links survive -----------------------------------------------------------------------------

    def reduced(self, joint: UrdfJoint) -> bool:
        return (
            self.options.lump
            and joint.type == "fixed"
            and joint.parent != "world"
            and joint.name not in self.preserve
            and joint.name not in self.locked
        )

    def survivor(self, link: str) -> tuple[str, Pose]:
        """The link `link` is lumped into (itself if none) and `link`'s frame in that link's frame."""
        pose = Pose()
        while True:
            pj = self.robot.parent_joint(link)
            if pj is None or not self.reduced(pj):
                return link, pose
            pose = pj.origin.compose(pose)
            link = pj.parent

    def lumped_subtree(self, link: str) -> list[str]:
        """Links welded to `link` by reduced fixed joints, depth first in urdfdom's child order."""
        out = []
        for jn in self.robot.children_of[link]:
            joint = self.robot.joints[jn]
            if self.reduced(joint):
                out.append(joint.child)
                out.extend(self.lumped_subtree(joint.child))
        return out

    def body(self, name: str) -> _Body:
        link = self.robot.links[name]
        mass = None
        if link.inertial is not None:
            mass = MassProperties(link.inertial.mass_kg, link.inertial.origin, link.inertial.inertia)
        b = _Body(name, mass)
        members = [name, *self.lumped_subtree(name)] if self.options.lump else [name]
        for member in members:
            m_link = self.robot.links[member]
            _, in_body = self.survivor(member) if member != name else (name, Pose())
            if member != name and m_link.inertial is not None:
                i = m_link.inertial
                b.mass = merge(b.mass, MassProperties(i.mass_kg, i.origin, i.inertia), in_body)
            for shape in m_link.visuals:
                b.visuals.append((shape, in_body.compose(shape.origin), shape.name or member))
            for shape in m_link.collisions:
                b.collisions.append((shape, in_body.compose(shape.origin), shape.name or member))
        return b

    # --- SDF elements ------------------------------------------------------------------------------------

    def geometry(self, parent: Element, g: UrdfGeometry, line: int) -> None:
        geo = _sub(parent, "geometry", line=line)
        if g.kind == "box":
            _sub(_sub(geo, "box", line=line), "size", " ".join(_num(v) for v in g.size_m), line)
        elif g.kind == "cylinder":
            cyl = _sub(geo, "cylinder", line=line)
            _sub(cyl, "radius", _num(g.radius_m), line)
            _sub(cyl, "length", _num(g.length_m), line)
        elif g.kind == "sphere":
            _sub(_sub(geo, "sphere", line=line), "radius", _num(g.radius_m), line)
        else:
            mesh = _sub(geo, "mesh", line=line)
            uri = g.filename
            if self.options.resolve_meshes:
                uri = str(resolve_mesh(g.filename, self.options.base_dir, self.robot.source, g.line or line))
            _sub(mesh, "uri", uri, line)
            _sub(mesh, "scale", " ".join(_num(v) for v in g.scale), line)

    def shapes(self, link_el: Element, body: _Body, kind: str) -> list[tuple[Element, str]]:
        out = []
        items = body.visuals if kind == "visual" else body.collisions
        for count, (shape, pose, base) in enumerate(items):
            name = f"{base}_{kind}" + (f"_{count}" if count else "")
            if not name.startswith(body.name):  # sdformat marks names that do not start with the link's
                name = body.name + LUMP_PREFIX + name
            el = _sub(link_el, kind, line=shape.line, name=name)
            _sub(el, "pose", _pose_text(pose), shape.line)
            try:
                self.geometry(el, shape.geometry, shape.line)
            except MeshNotFound as e:  # Gazebo loads the robot without that shape
                link_el.remove(el)
                report_missing_mesh(e, kind)
                continue
            if shape.geometry.kind == "mesh":  # keyed by the shape's place among those the link keeps
                self.mesh_uris[(body.name, kind, len(out))] = shape.geometry.filename
            if kind == "visual" and shape.rgba is not None:
                mat = _sub(el, "material", line=shape.line)
                rgba = " ".join(_num(c) for c in shape.rgba)
                _sub(mat, "ambient", rgba, shape.line)
                _sub(mat, "diffuse", rgba, shape.line)
            out.append((el, shape.origin_link))
        return out

    def link_element(self, model: Element, body: _Body, pose_parent: str | None, pose: Pose) -> Element:
        link = self.robot.links[body.name]
        el = _sub(model, "link", line=link.line, name=body.name)
        if pose_parent is not None:
            _sub(el, "pose", _pose_text(pose), link.line, relative_to=pose_parent)
        if body.mass is not None and body.mass.mass_kg > 0:
            line = link.inertial.line if link.inertial is not None else link.line
            inertial = _sub(el, "inertial", line=line)
            _sub(inertial, "pose", _pose_text(body.mass.frame), line)
            _sub(inertial, "mass", _num(body.mass.mass_kg), line)
            inertia = _sub(inertial, "inertia", line=line)
            for key, value in zip(("ixx", "ixy", "ixz", "iyy", "iyz", "izz"), body.mass.inertia_kg_m2, strict=True):
                _sub(inertia, key, _num(value), line)
        collisions = self.shapes(el, body, "collision")
        visuals = self.shapes(el, body, "visual")
        for ext in self.extensions:
            if not ext.reference or ext.reference not in self.robot.links:
                continue
            owner, _ = self.survivor(ext.reference)
            if owner != body.name:
                continue
            for c, origin in collisions:
                if origin == ext.origin_link:
                    apply_to_collision(ext, c)
            for v, origin in visuals:
                if origin == ext.origin_link:
                    apply_to_visual(ext, v)
            apply_to_link(ext, el, ext.origin_link if ext.origin_link != body.name else None)
        return el

    def joint_element(self, model: Element, joint: UrdfJoint, parent: str, origin: Pose) -> Element | None:
        kind = joint.type
        if kind in ("floating", "planar"):
            if self.options.lump:
                self.ignored.append(f"joint {joint.name!r} is {kind}: Gazebo makes no joint of it (a free link)")
                return None
            self.ignored.append(f"joint {joint.name!r} is {kind}: treated as fixed, as robot_state_publisher does")
            kind = "fixed"
        locked = joint.name in self.locked
        if locked:
            kind = "revolute"
        elif kind == "continuous" and self.options.lump:
            kind = "revolute"  # sdformat: a revolute joint without position limits
        el = _sub(model, "joint", line=joint.line, name=joint.name, type=kind)
        _sub(el, "pose", _pose_text(origin), joint.line, relative_to="__model__" if parent == "world" else parent)
        _sub(el, "parent", parent, joint.line)
        _sub(el, "child", joint.child, joint.line)
        if kind == "fixed":
            return el
        axis = _sub(el, "axis", line=joint.line)
        _sub(axis, "xyz", " ".join(_num(v) for v in joint.axis), joint.line)
        limit = _sub(axis, "limit", line=joint.line)
        dynamics = _sub(axis, "dynamics", line=joint.line)
        if locked:
            _sub(limit, "lower", "0", joint.line)
            _sub(limit, "upper", "0", joint.line)
        elif joint.limit is not None:
            lo, hi = joint.limit.lower, joint.limit.upper
            if joint.type not in ("continuous",):
                lo, hi = min(lo, hi), max(lo, hi)  # sdformat swaps reversed limits (with a warning)
                _sub(limit, "lower", _num(lo), joint.line)
                _sub(limit, "upper", _num(hi), joint.line)
            _sub(limit, "effort", _num(joint.limit.effort), joint.line)
            _sub(limit, "velocity", _num(joint.limit.velocity), joint.line)
        if joint.damping is not None:
            _sub(dynamics, "damping", _num(joint.damping), joint.line)
            _sub(dynamics, "friction", _num(joint.friction), joint.line)
        if joint.mimic is not None:
            mimic = _sub(axis, "mimic", line=joint.line, joint=joint.mimic.joint)
            _sub(mimic, "multiplier", _num(joint.mimic.multiplier), joint.line)
            _sub(mimic, "offset", _num(joint.mimic.offset), joint.line)
        return el

    # --- the model ---------------------------------------------------------------------------------------

    def convert(self, name: str) -> tuple[Element, set[str]]:
        r = self.robot
        sdf = etree.Element("sdf", version=SDF_VERSION)
        model = _sub(sdf, "model", line=r.line, name=name)
        emitted: set[str] = set()
        joints_out: set[str] = set()
        self._emit(model, r.root, emitted, joints_out)
        if not emitted:
            raise DescriptionError(
                f"robot {r.name!r}: no link has mass, so Gazebo would model nothing",
                source=r.source,
                line=r.links[r.root].line,
                field=f"link[{r.root}]",
                hint="give the root link (or a link fixed to it) an <inertial> with a positive <mass>",
            )
        if self.options.lump:
            self._frames(model, emitted)
        for ext in self.extensions:
            self._place(model, ext, emitted, joints_out)
        for block in r.ros2_control:
            item = copy.deepcopy(block)
            for j in list(item.findall("joint")):
                if j.get("name") not in joints_out and (j.get("name") or "") in r.joints:
                    # gz_ros2_control skips joints the model lacks, with a warning
                    self.ignored.append(
                        f"ros2_control joint {j.get('name')!r} is not a joint of the simulated model (lumped or "
                        "dropped): skipped as gz_ros2_control does"
                    )
                    item.remove(j)
            model.append(item)
        return sdf, emitted

    def _emit(self, model: Element, link: str, emitted: set[str], joints_out: set[str]) -> None:
        r = self.robot
        pj = r.parent_joint(link)
        lumped = pj is not None and self.reduced(pj)
        if not lumped and link != "world":
            body = self.body(link)
            massless = body.mass is None or body.mass.mass_kg <= 0
            if massless and self.options.lump:
                self.ignored.append(
                    f"link {link!r} has no mass (no <inertial> or mass 0): not modeled in sdf, "
                    + ("nor its child links" if r.children_of[link] else "as Gazebo does")
                )
                return
            if pj is None:
                self.link_element(model, body, None, Pose())
            else:
                parent, in_parent = self.survivor(pj.parent) if pj.parent != "world" else ("world", Pose())
                origin = in_parent.compose(pj.origin)
                if self.joint_element(model, pj, parent, origin) is None:
                    ref = "__model__" if parent == "world" else parent
                    self.link_element(model, body, ref, origin)
                else:
                    joints_out.add(pj.name)
                    self.link_element(model, body, pj.name, Pose())
            emitted.add(link)
        for jn in r.children_of[link]:
            self._emit(model, r.joints[jn].child, emitted, joints_out)

    def _frames(self, model: Element, emitted: set[str]) -> None:
        """Reduced joints and lumped links live on as frames (sdformat's //model/frame memorials)."""
        for joint in self.robot.joints.values():
            if not self.reduced(joint) or self.survivor(joint.parent)[0] not in emitted:
                continue
            frame = _sub(model, "frame", line=joint.line, name=joint.name, attached_to=joint.parent)
            _sub(frame, "pose", _pose_text(joint.origin), joint.line)
            _sub(model, "frame", line=joint.line, name=joint.child, attached_to=joint.name)

    def _place(self, model: Element, ext: GazeboExtension, emitted: set[str], joints_out: set[str]) -> None:
        r = self.robot
        if not ext.reference:
            apply_to_model(ext, model)
        elif ext.reference in r.links:
            if self.survivor(ext.reference)[0] not in emitted:
                self.ignored.append(f"<gazebo reference={ext.reference!r}> (line {ext.line}): link is not modeled")
        elif ext.reference in r.joints:
            if ext.reference in joints_out:
                el = next(j for j in model.findall("joint") if j.get("name") == ext.reference)
                apply_to_joint(ext, el)
        else:
            self.ignored.append(f"<gazebo reference={ext.reference!r}> (line {ext.line}) names no link or joint")


@dataclass(frozen=True)
class Conversion:
    sdf: Element  # <sdf version="1.11"><model>…
    ignored: tuple[str, ...]  # one line for each thing Gazebo would drop or not simulate
    mesh_uris: dict[tuple[str, str, int], str]  # (link, "visual"|"collision", index) → the URI the URDF gave


def urdf_to_sdf(robot: UrdfRobot, options: ConversionOptions, name: str | None = None) -> Conversion:
    """The `<sdf><model>` Gazebo makes of `robot`."""
    conv = _Converter(robot, options)
    sdf, _ = conv.convert(name or robot.name)
    return Conversion(sdf, tuple(conv.ignored), dict(conv.mesh_uris))
