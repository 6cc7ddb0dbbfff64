"""URDF text → a validated `UrdfRobot`: links, joints, materials, and the raw `<gazebo>`/`<ros2_control>` elements.

Follows urdfdom's rules for what a valid URDF is (one root link, a tree of joints, `<limit>` with effort and
velocity on revolute and prismatic joints, every inertia component given), and reports the first problem as a
DescriptionError naming the file, the line and the element. Nothing here knows about Gazebo or fixed-joint
lumping: that is `to_sdf`'s job.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import NoReturn

from lxml import etree

from diffctl.description.pose import Pose, Vec3
from diffctl.errors import DescriptionError, suggest, xml_error

Element = etree._Element

URDF_JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")
GEOMETRY_TAGS = ("box", "cylinder", "sphere", "mesh")
RGBA = tuple[float, float, float, float]


@dataclass(frozen=True)
class UrdfGeometry:
    kind: str  # one of GEOMETRY_TAGS
    size_m: Vec3 = (0.0, 0.0, 0.0)  # box
    radius_m: float = 0.0  # cylinder, sphere
    length_m: float = 0.0  # cylinder
    filename: str = ""  # mesh URI as written (package://, file://, model://, relative or absolute)
    scale: Vec3 = (1.0, 1.0, 1.0)  # mesh
    line: int = 0  # of the shape element, for errors about the file it names


@dataclass(frozen=True)
class UrdfShape:
    """A `<visual>` or `<collision>`; `origin_link` names the link it was written in (it survives lumping)."""

    name: str  # the name attribute, '' when absent
    origin: Pose  # in the owning link's frame
    geometry: UrdfGeometry
    origin_link: str
    line: int
    rgba: RGBA | None = None  # visuals: the material colour (inline or by name)
    texture: str = ""


@dataclass(frozen=True)
class UrdfInertial:
    mass_kg: float
    origin: Pose  # centre of mass and inertia frame, in the link frame
    inertia: tuple[float, float, float, float, float, float]  # ixx ixy ixz iyy iyz izz
    line: int


@dataclass(frozen=True)
class UrdfLink:
    name: str
    inertial: UrdfInertial | None
    visuals: tuple[UrdfShape, ...]
    collisions: tuple[UrdfShape, ...]
    line: int


@dataclass(frozen=True)
class UrdfLimit:
    lower: float
    upper: float
    effort: float
    velocity: float


@dataclass(frozen=True)
class UrdfSafety:
    """`<safety_controller>`: the soft position range and the gains of the limiter that keeps to it."""

    soft_lower_limit: float
    soft_upper_limit: float
    k_position: float
    k_velocity: float


@dataclass(frozen=True)
class UrdfMimic:
    joint: str
    multiplier: float
    offset: float


@dataclass(frozen=True)
class UrdfJoint:
    name: str
    type: str  # one of URDF_JOINT_TYPES
    parent: str
    child: str
    origin: Pose  # the joint (and child link) frame in the parent link frame
    axis: Vec3
    line: int
    limit: UrdfLimit | None = None
    damping: float | None = None  # <dynamics damping friction>; None when no <dynamics>
    friction: float = 0.0
    mimic: UrdfMimic | None = None
    safety: UrdfSafety | None = None


@dataclass(frozen=True)
class UrdfRobot:
    name: str
    source: str
    links: dict[str, UrdfLink]
    joints: dict[str, UrdfJoint]  # in document order
    root: str
    gazebo: tuple[Element, ...] = ()
    ros2_control: tuple[Element, ...] = ()
    line: int = 0
    children_of: dict[str, tuple[str, ...]] = field(default_factory=dict)  # link → child joints, by joint name

    def parent_joint(self, link: str) -> UrdfJoint | None:
        for j in self.joints.values():
            if j.child == link:
                return j
        return None


class _Reader:
    def __init__(self, source: str) -> None:
        self.source = source

    def fail(self, el: Element | None, message: str, hint: str | None = None) -> NoReturn:
        path = []
        node = el
        while node is not None and isinstance(node.tag, str):
            name = node.get("name")
            path.append(f"{node.tag}[{name}]" if name else str(node.tag))
            node = node.getparent()
        raise DescriptionError(
            message,
            source=self.source,
            line=el.sourceline if el is not None else None,
            field="/".join(reversed(path)) or None,
            hint=hint,
        )

    def floats(self, el: Element, attr: str, n: int, default: tuple[float, ...] | None) -> tuple[float, ...]:
        text = el.get(attr)
        if text is None:
            if default is None:
                self.fail(el, f"<{el.tag}> needs a {attr!r} attribute")
            return default
        parts = text.split()
        what = "a number" if n == 1 else f"{n} numbers"
        try:
            values = tuple(float(p) for p in parts)
        except ValueError:
            self.fail(el, f"<{el.tag} {attr}> must be {what}, got {text!r}")
        if len(values) != n:
            self.fail(el, f"<{el.tag} {attr}> must be {what}, got {text!r}")
        if not all(math.isfinite(v) for v in values):
            self.fail(el, f"<{el.tag} {attr}> must hold finite numbers, got {text!r}")
        return values

    def number(self, el: Element, attr: str, default: float | None = None) -> float:
        return self.floats(el, attr, 1, None if default is None else (default,))[0]

    def name(self, el: Element) -> str:
        value = (el.get("name") or "").strip()
        if not value:
            self.fail(el, f"<{el.tag}> needs a non-empty 'name' attribute")
        return value

    def origin(self, parent: Element) -> Pose:
        el = parent.find("origin")
        if el is None:
            return Pose()
        xyz = self.floats(el, "xyz", 3, (0.0, 0.0, 0.0))
        rpy = self.floats(el, "rpy", 3, (0.0, 0.0, 0.0))
        return Pose.from_xyz_rpy(xyz, rpy)

    def rgba(self, el: Element) -> RGBA:
        values = self.floats(el, "rgba", 4, None)
        if not all(0.0 <= v <= 1.0 for v in values):
            self.fail(el, f"<color rgba> values must lie in [0, 1], got {el.get('rgba')!r}")
        return (values[0], values[1], values[2], values[3])

    def geometry(self, shape: Element) -> UrdfGeometry:
        geo = shape.find("geometry")
        if geo is None:
            self.fail(shape, f"<{shape.tag}> needs a <geometry>", hint="one of " + ", ".join(GEOMETRY_TAGS))
        kids = [c for c in geo if isinstance(c.tag, str)]
        if len(kids) != 1 or kids[0].tag not in GEOMETRY_TAGS:
            found = ", ".join(f"<{c.tag}>" for c in kids) or "nothing"
            hint = suggest(kids[0].tag, GEOMETRY_TAGS) if len(kids) == 1 else ""
            self.fail(geo, f"<geometry> must hold exactly one of {', '.join(GEOMETRY_TAGS)}; found {found}{hint}")
        g = kids[0]
        # urdfdom checks no size (a zero box is a placeholder some robots carry); the simulator leaves out a
        # shape with no volume
        if g.tag == "box":
            size = self.floats(g, "size", 3, None)
            return UrdfGeometry("box", size_m=(size[0], size[1], size[2]))
        if g.tag == "cylinder":
            radius, length = self.number(g, "radius"), self.number(g, "length")
            return UrdfGeometry("cylinder", radius_m=radius, length_m=length)
        if g.tag == "sphere":
            return UrdfGeometry("sphere", radius_m=self.number(g, "radius"))
        filename = (g.get("filename") or "").strip()
        if not filename:
            self.fail(g, "<mesh> needs a 'filename' attribute", hint='e.g. filename="package://my_pkg/meshes/a.stl"')
        scale = self.floats(g, "scale", 3, (1.0, 1.0, 1.0))
        return UrdfGeometry("mesh", filename=filename, scale=(scale[0], scale[1], scale[2]), line=g.sourceline or 0)

    def material(self, el: Element, named: dict[str, tuple[RGBA | None, str]]) -> tuple[RGBA | None, str]:
        """(colour, texture) of a `<material>`: inline, or by name from the robot's top-level materials."""
        color_el = el.find("color")
        texture_el = el.find("texture")
        rgba = self.rgba(color_el) if color_el is not None else None
        texture = (texture_el.get("filename") or "").strip() if texture_el is not None else ""
        name = (el.get("name") or "").strip()
        if rgba is None and not texture and name:
            if name in named:
                return named[name]
            # urdfdom logs this and keeps the visual, uncoloured (model.cpp's assignMaterial result is unused)
            link = el.getparent().getparent() if el.getparent() is not None else None
            link_name = link.get("name") if link is not None else None
            _warn_once(
                f"{self.source}:{el.sourceline}: link {link_name!r} material {name!r} undefined"
                f"{suggest(name, named)}; its visual keeps the default colour"
            )
            return None, ""
        if name and name not in named:
            named[name] = (rgba, texture)  # a named inline material serves later visuals, as urdfdom's model map does
        return rgba, texture


_warned: set[str] = set()


def _warn_once(message: str) -> None:
    if message not in _warned:
        _warned.add(message)
        from diffctl.console import warn

        warn(message)


def _inertial(r: _Reader, link: Element) -> UrdfInertial | None:
    el = link.find("inertial")
    if el is None:
        return None
    mass_el = el.find("mass")
    if mass_el is None:
        r.fail(el, "<inertial> needs <mass value=…/> (kilograms)")
    mass = r.number(mass_el, "value")  # urdfdom checks no value: Gazebo drops a link of mass <= 0
    inertia_el = el.find("inertia")
    if inertia_el is None:
        r.fail(el, "<inertial> needs <inertia ixx ixy ixz iyy iyz izz/>")
    keys = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
    inertia = tuple(r.number(inertia_el, k) for k in keys)
    return UrdfInertial(mass, r.origin(el), inertia, el.sourceline or 0)  # type: ignore[arg-type]


def _link(r: _Reader, el: Element, named: dict[str, tuple[RGBA | None, str]]) -> UrdfLink:
    name = r.name(el)
    visuals = []
    for v in el.findall("visual"):
        rgba, texture = None, ""
        mat = v.find("material")
        if mat is not None:
            rgba, texture = r.material(mat, named)
        visuals.append(
            UrdfShape((v.get("name") or "").strip(), r.origin(v), r.geometry(v), name, v.sourceline or 0, rgba, texture)
        )
    collisions = [
        UrdfShape((c.get("name") or "").strip(), r.origin(c), r.geometry(c), name, c.sourceline or 0)
        for c in el.findall("collision")
    ]
    return UrdfLink(name, _inertial(r, el), tuple(visuals), tuple(collisions), el.sourceline or 0)


def _joint(r: _Reader, el: Element, links: dict[str, UrdfLink]) -> UrdfJoint:
    name = r.name(el)
    kind = (el.get("type") or "").strip()
    if kind not in URDF_JOINT_TYPES:
        r.fail(
            el,
            f"joint type {kind!r} is not a URDF joint type{suggest(kind, URDF_JOINT_TYPES)}",
            hint="valid: " + ", ".join(URDF_JOINT_TYPES),
        )
    ends = {}
    for tag in ("parent", "child"):
        end = el.find(tag)
        value = (end.get("link") or "").strip() if end is not None else ""
        if not value:
            r.fail(end if end is not None else el, f"joint {name!r} needs <{tag} link=…/>")
        if value not in links:
            r.fail(end, f"joint {name!r}: {tag} link {value!r} is not defined{suggest(value, links)}")
        ends[tag] = value
    if ends["parent"] == ends["child"]:
        r.fail(el, f"joint {name!r} connects link {ends['child']!r} to itself")
    axis: Vec3 = (1.0, 0.0, 0.0)  # urdfdom's default
    axis_el = el.find("axis")
    if axis_el is not None and kind not in ("fixed", "floating"):
        xyz = r.floats(axis_el, "xyz", 3, (1.0, 0.0, 0.0))
        norm = math.sqrt(sum(c * c for c in xyz))
        # urdfdom keeps a zero axis (the joint never moves); sdformat refuses it when the robot is simulated
        axis = (xyz[0] / norm, xyz[1] / norm, xyz[2] / norm) if norm > 0 else (0.0, 0.0, 0.0)
    limit = None
    limit_el = el.find("limit")
    if limit_el is not None:
        for attr in ("effort", "velocity"):
            if limit_el.get(attr) is None:  # urdfdom refuses a limit without them
                r.fail(limit_el, f"joint {name!r}: <limit> needs a {attr!r} attribute")
        limit = UrdfLimit(
            r.number(limit_el, "lower", 0.0),
            r.number(limit_el, "upper", 0.0),
            r.number(limit_el, "effort"),
            r.number(limit_el, "velocity"),
        )
    elif kind in ("revolute", "prismatic"):
        r.fail(
            el,
            f"joint {name!r} is {kind} but has no <limit>",
            hint='add <limit lower="…" upper="…" effort="…" velocity="…"/>, or make it continuous',
        )
    damping, friction = None, 0.0
    dyn = el.find("dynamics")
    if dyn is not None:
        damping, friction = r.number(dyn, "damping", 0.0), r.number(dyn, "friction", 0.0)
    mimic = None
    mimic_el = el.find("mimic")
    if mimic_el is not None:
        target = (mimic_el.get("joint") or "").strip()
        if not target:
            r.fail(mimic_el, "<mimic> needs a 'joint' attribute")
        mimic = UrdfMimic(target, r.number(mimic_el, "multiplier", 1.0), r.number(mimic_el, "offset", 0.0))
    safety = None
    safety_el = el.find("safety_controller")
    if safety_el is not None:
        if safety_el.get("k_velocity") is None:  # urdfdom refuses the joint without it; the rest default to 0
            r.fail(safety_el, f"joint {name!r}: <safety_controller> needs a 'k_velocity' attribute")
        safety = UrdfSafety(
            r.number(safety_el, "soft_lower_limit", 0.0),
            r.number(safety_el, "soft_upper_limit", 0.0),
            r.number(safety_el, "k_position", 0.0),
            r.number(safety_el, "k_velocity"),
        )
    return UrdfJoint(
        name,
        kind,
        ends["parent"],
        ends["child"],
        r.origin(el),
        axis,
        el.sourceline or 0,
        limit,
        damping,
        friction,
        mimic,
        safety,
    )


def parse_root(text: str, source: str) -> Element:
    try:
        return etree.fromstring(text.encode(), parser=etree.XMLParser(remove_comments=True, resolve_entities=False))
    except etree.XMLSyntaxError as e:
        raise xml_error(e, source) from None


def parse_urdf(text_or_root: str | Element, source: str = "<string>") -> UrdfRobot:
    """A URDF document (text or its parsed root element) as a validated UrdfRobot."""
    root = parse_root(text_or_root, source) if isinstance(text_or_root, str) else text_or_root
    r = _Reader(source)
    if root.tag != "robot":
        r.fail(root, f"the root element of a URDF must be <robot>, got <{root.tag}>")
    robot_name = r.name(root)
    named: dict[str, tuple[RGBA | None, str]] = {}
    for m in root.findall("material"):
        name = r.name(m)
        if name in named:
            r.fail(m, f"material {name!r} is not unique", hint="give each top-level <material> its own name")
        if m.find("color") is None and m.find("texture") is None:
            # urdfdom logs an error for it and keeps the material, without a colour
            _warn_once(f"{source}:{m.sourceline}: Material [{name}] color has no rgba")
            named[name] = (None, "")
            continue
        named[name] = r.material(m, {})
    links: dict[str, UrdfLink] = {}
    for el in root.findall("link"):
        link = _link(r, el, named)
        if link.name in links:
            r.fail(el, f"link {link.name!r} is defined twice (first on line {links[link.name].line})")
        links[link.name] = link
    if not links:
        r.fail(root, f"robot {robot_name!r} has no <link>")
    joints: dict[str, UrdfJoint] = {}
    parent_of: dict[str, str] = {}
    for el in root.findall("joint"):
        joint = _joint(r, el, links)
        if joint.name in joints:
            r.fail(el, f"joint {joint.name!r} is defined twice (first on line {joints[joint.name].line})")
        if joint.name in links:
            r.fail(
                el,
                f"joint {joint.name!r} has the name of link {joint.name!r} (line {links[joint.name].line})",
                hint=f"in SDF, which Gazebo turns a URDF into, links and joints share names: rename the joint, "
                f"e.g. {joint.name + '_joint'!r}",
            )
        if joint.child in parent_of:
            r.fail(el, f"link {joint.child!r} is the child of joints {parent_of[joint.child]!r} and {joint.name!r}")
        parent_of[joint.child] = joint.name
        joints[joint.name] = joint
    for joint in joints.values():
        if joint.mimic is not None and joint.mimic.joint not in joints:
            mimic_el = next(e for e in root.findall("joint") if e.get("name") == joint.name).find("mimic")
            r.fail(mimic_el, f"joint {joint.name!r} mimics {joint.mimic.joint!r}, which is not a joint")
    roots = [name for name in links if name not in parent_of]
    if len(roots) != 1:
        what = "no root link (the joints form a loop)" if not roots else f"{len(roots)} root links: {', '.join(roots)}"
        hint = "a URDF is one tree: every link but the root needs a joint"
        r.fail(root, f"robot {robot_name!r} has {what}", hint=hint)
    children: dict[str, list[str]] = {name: [] for name in links}
    for joint in joints.values():
        children[joint.parent].append(joint.name)
    # A loop detached from the root leaves links unreachable even with exactly one root.
    reached, todo = {roots[0]}, [roots[0]]
    while todo:
        for jn in children[todo.pop()]:
            reached.add(joints[jn].child)
            todo.append(joints[jn].child)
    if len(reached) != len(links):
        lost = sorted(set(links) - reached)
        r.fail(root, f"links {', '.join(lost)} are not connected to root link {roots[0]!r} (the joints form a loop)")
    # urdfdom keeps joints in a name-sorted map, so child order (and with it lumped names) follows joint names.
    children_of = {name: tuple(sorted(kids)) for name, kids in children.items()}
    return UrdfRobot(
        robot_name,
        source,
        links,
        joints,
        roots[0],
        tuple(root.findall("gazebo")),
        tuple(root.findall("ros2_control")),
        root.sourceline or 0,
        children_of,
    )
