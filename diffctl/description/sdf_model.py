"""One top-level SDF model, nested models and includes flattened, built into a frozen `model.Model`.

Three passes: collect every frame-bearing element into a FrameGraph (so names may be used before they are
defined), resolve `attached_to`, joint parent/child and `relative_to` references, then build the dataclasses
with every pose resolved and check what physics needs (a tree of joints, mass on every moving body).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from diffctl.description.missing_mesh import MeshNotFound, report_missing_mesh
from diffctl.description.model import (
    JOINT_TYPES,
    Frame,
    Joint,
    JointDynamics,
    JointLimits,
    Link,
    Model,
    Plugin,
    Ros2Control,
    Sensor,
)
from diffctl.description.pose import Pose
from diffctl.description.ros2_control import parse_ros2_control
from diffctl.description.sdf_documents import Include, read_include, stack_key
from diffctl.description.sdf_elements import (
    ToLink,
    parse_collision,
    parse_inertial,
    parse_plugin,
    parse_sensor,
    parse_visual,
)
from diffctl.description.sdf_frames import MODEL_FRAME, FrameGraph, Node, Scope
from diffctl.description.sdf_values import (
    Doc,
    Element,
    bool_value,
    child,
    child_text,
    children,
    fail,
    float_value,
    parse_floats,
    pose_child,
    required_attr,
)
from diffctl.errors import DescriptionError, suggest

UNSUPPORTED_JOINT_TYPES = ("universal", "revolute2", "screw", "gearbox")

# --- one top-level model ------------------------------------------------------------------------------------


@dataclass
class _Ref:
    node: Node
    scope: Scope
    text: str | None  # as written; None → the default
    default: str | None  # key used when text is None


@dataclass
class _Builder:
    """Collects a model tree into a FrameGraph, resolves references, then builds the frozen Model."""

    name: str
    graph: FrameGraph = field(default_factory=FrameGraph)
    links: list[tuple[str, Scope]] = field(default_factory=list)
    joints: list[tuple[str, Scope]] = field(default_factory=list)
    frames: list[tuple[str, Scope]] = field(default_factory=list)
    models: list[str] = field(default_factory=list)
    plugins: list[tuple[Doc, Element]] = field(default_factory=list)
    ros2_control: list[tuple[Doc, Element]] = field(default_factory=list)
    attach_refs: list[_Ref] = field(default_factory=list)
    pose_refs: list[_Ref] = field(default_factory=list)
    joint_refs: dict[str, tuple[str, str]] = field(default_factory=dict)  # joint key → (parent key|world, child key)

    def collect(self, doc: Doc, el: Element, scope: Scope, stack: tuple[str, ...]) -> None:
        for c in el:
            tag = c.tag
            if tag == "link":
                node = self._node(doc, c, scope, "link")
                self.pose_refs.append(_Ref(node, scope, node.relative_ref, scope.model_key))
                self.links.append((node.key, scope))
            elif tag == "joint":
                node = self._node(doc, c, scope, "joint")
                self.joints.append((node.key, scope))
            elif tag == "frame":
                node = self._node(doc, c, scope, "frame")
                attached = (c.get("attached_to") or "").strip() or None
                self.attach_refs.append(_Ref(node, scope, attached, scope.model_key))
                self.frames.append((node.key, scope))
            elif tag == "model":
                self._nested(doc, c, scope, required_attr(doc, c, "name"), stack, None)
            elif tag == "include":
                inc = read_include(doc, c, stack)
                if inc is None or inc.is_light:
                    continue  # a skipped missing Fuel model; lights are the world's business
                if inc.merge:
                    self._merge(doc, c, scope, inc, (*stack, stack_key(inc.doc)))
                    self.plugins.extend((doc, p) for p in children(c, "plugin"))  # appended to the included model
                    continue
                self._nested(
                    inc.doc,
                    inc.model_el,
                    scope,
                    inc.name,
                    (*stack, stack_key(inc.doc)),
                    inc,
                    include_el=c,
                    include_doc=doc,
                )
                self.plugins.extend((doc, p) for p in children(c, "plugin"))  # appended to the included model
            elif tag == "plugin":
                self.plugins.append((doc, c))
            elif tag == "ros2_control":
                self.ros2_control.append((doc, c))
        if scope.canonical is None:
            wanted = (el.get("canonical_link") or "").strip()
            if wanted:
                key = scope.lookup(wanted)
                if key is None or self.graph.nodes[key].kind != "link":
                    fail(doc, el, f"canonical_link {wanted!r} is not a link of this model")
                scope.canonical = key
            else:
                first = next((k for k, s in self.links if s is scope), None)
                if first is None:
                    first = next((s.canonical for s in scope.merged if s.canonical), None)
                if first is None:
                    first = next((s.canonical for s in scope.children.values() if s.canonical), None)
                if first is None:
                    fail(doc, el, f"model {el.get('name')!r} has no <link>", hint="a model needs at least one link")
                scope.canonical = first

    def _node(self, doc: Doc, el: Element, scope: Scope, kind: str) -> Node:
        name = required_attr(doc, el, "name")
        pose, rel, pose_el = pose_child(doc, el)
        node = Node(scope.prefix + name, kind, pose, doc, el, relative_ref=rel, pose_el=pose_el)
        self.graph.add(node, scope, name)
        return node

    def _nested(
        self,
        doc: Doc,
        el: Element,
        scope: Scope,
        name: str,
        stack: tuple[str, ...],
        inc: Include | None,
        include_el: Element | None = None,
        include_doc: Doc | None = None,
    ) -> None:
        pose, rel, pose_el = pose_child(doc, el)
        placement = (el.get("placement_frame") or "").strip() or None
        node_doc, node_el = doc, el
        if inc is not None:
            if inc.pose is not None:
                pose, rel, pose_el = inc.pose, inc.pose_rel, inc.pose_el
            placement = inc.placement or placement
            node_doc, node_el = include_doc or doc, include_el if include_el is not None else el
        key = scope.prefix + name
        node = Node(key, "model", pose, node_doc, node_el, relative_ref=rel, pose_el=pose_el)
        self.graph.add(node, scope, name)
        # A relative_to on an include names a frame of the including scope: resolve there.
        self.pose_refs.append(_Ref(node, scope, rel, scope.model_key))
        sub = Scope(prefix=key + "::", model_key=key)
        scope.children[name] = sub
        self.models.append(key)
        self.collect(doc, el, sub, stack)
        node.attached_to = sub.canonical
        if placement is not None:
            node.placement = self.graph.resolve_ref(sub, placement, node_doc, node_el, "placement_frame")

    def _merge(self, doc: Doc, include_el: Element, scope: Scope, inc: Include, stack: tuple[str, ...]) -> None:
        """`<include merge="true">` (SDF 1.9, sdformat's insertIncludedElement): the included model's links,
        joints, frames, nested models and plugins join `scope` under their own names; what referred to its
        `__model__` now refers to the proxy frame `_merged__<name>__model__`, attached to its canonical link
        and posed where the include puts the model."""
        if inc.pose is not None:
            pose, rel, pose_el = inc.pose, inc.pose_rel, inc.pose_el
        else:
            pose, rel, pose_el = pose_child(inc.doc, inc.model_el)
        proxy_name = f"_merged__{inc.name}__model__"
        proxy = Node(scope.prefix + proxy_name, "frame", pose, doc, include_el, relative_ref=rel, pose_el=pose_el)
        self.graph.add(proxy, scope, proxy_name)
        self.pose_refs.append(_Ref(proxy, scope, rel, scope.model_key))
        self.frames.append((proxy.key, scope))
        view = scope.merged_view(proxy.key)
        self.collect(inc.doc, inc.model_el, view, stack)
        proxy.attached_to = view.canonical
        placement = inc.placement or (inc.model_el.get("placement_frame") or "").strip() or None
        if placement is not None:
            proxy.placement = self.graph.resolve_ref(view, placement, doc, include_el, "placement_frame")

    def resolve(self, top: Scope) -> None:
        g = self.graph
        for ref in self.attach_refs:
            ref.node.attached_to = (
                g.resolve_ref(ref.scope, ref.text, ref.node.doc, ref.node.el, "attached_to")
                if ref.text
                else ref.default
            )
            # A frame's pose is relative to the frame it is attached to unless it says otherwise.
            self.pose_refs.append(_Ref(ref.node, ref.scope, ref.node.relative_ref, ref.node.attached_to))
        for key, scope in self.joints:
            node = g.nodes[key]
            parent_text = child_text(node.el, "parent")
            child_name = child_text(node.el, "child")
            if not parent_text or not child_name:
                fail(node.doc, node.el, "a <joint> needs non-empty <parent> and <child>")
            if child_name == "world":
                fail(node.doc, child(node.el, "child"), "a joint's <child> cannot be 'world'")
            child_key = g.resolve_ref(scope, child_name, node.doc, child(node.el, "child"), "joint child")
            parent_key = (
                "world"
                if parent_text == "world"
                else g.resolve_ref(scope, parent_text, node.doc, child(node.el, "parent"), "joint parent")
            )
            self.joint_refs[key] = (parent_key, child_key)
            node.attached_to = child_key
            self.pose_refs.append(_Ref(node, scope, node.relative_ref, child_key))
        for ref in self.pose_refs:
            n = ref.node
            n.relative_to = (
                g.resolve_ref(ref.scope, ref.text, n.doc, n.pose_el, "relative_to") if ref.text else ref.default
            )
            if n.relative_to == n.key:
                fail(n.doc, n.pose_el, f"{n.kind} {n.key!r} cannot be relative_to itself")
        for key, (parent_key, child_key) in self.joint_refs.items():
            child_link = g.link_of(child_key)
            parent_link = "world" if parent_key == "world" else g.link_of(parent_key)
            if child_link == parent_link:
                node = g.nodes[key]
                fail(node.doc, node.el, f"joint {key!r} connects link {child_link!r} to itself")
            self.joint_refs[key] = (parent_link, child_link)

    def to_link(self, link_key: str, scope: Scope, doc: Doc) -> ToLink:
        g = self.graph

        def convert(pose: Pose, rel: str | None, pose_el: Element | None) -> Pose:
            if rel is None:
                return pose
            ref_key = g.resolve_ref(scope, rel, doc, pose_el, "relative_to")
            return g.pose_model(link_key).inverse().compose(g.pose_model(ref_key)).compose(pose)

        return convert


def _joint(b: _Builder, key: str, model_world: Pose) -> Joint:
    g = b.graph
    node = g.nodes[key]
    doc, el = node.doc, node.el
    kind = required_attr(doc, el, "type")
    if kind not in JOINT_TYPES:
        why = "is not supported by diffctl's simulator" if kind in UNSUPPORTED_JOINT_TYPES else "is not a joint type"
        fail(doc, el, f"joint type {kind!r} {why}{suggest(kind, JOINT_TYPES)}", hint="valid: " + ", ".join(JOINT_TYPES))
    parent, child_link = b.joint_refs[key]
    pose_model = g.pose_model(key)
    axis_model: tuple[float, float, float] | None = None
    limits, dynamics = JointLimits(), JointDynamics()
    axis_el = child(el, "axis")
    if kind in ("revolute", "continuous", "prismatic"):
        xyz = (0.0, 0.0, 1.0)
        frame = pose_model
        if axis_el is not None:
            xyz_el = child(axis_el, "xyz")
            if xyz_el is not None:
                xyz = parse_floats(doc, xyz_el, 3)
                expressed = (xyz_el.get("expressed_in") or "").strip()
                if expressed:
                    scope = next(s for k, s in b.joints if k == key)
                    frame = g.pose_model(g.resolve_ref(scope, expressed, doc, xyz_el, "expressed_in"))
                elif not doc.frames_v17 and bool_value(doc, axis_el, "use_parent_model_frame", False):
                    frame = Pose()
            norm = math.sqrt(sum(c * c for c in xyz))
            if norm == 0 and not doc.kinematics_only:  # (urdfdom keeps a zero axis: the joint never moves)
                fail(doc, xyz_el, "The norm of the xyz vector cannot be zero (joint axis <xyz>)")
            if norm > 0:
                xyz = (xyz[0] / norm, xyz[1] / norm, xyz[2] / norm)
            limits = _limits(doc, axis_el, kind)
            dyn = child(axis_el, "dynamics")
            if dyn is not None:
                dynamics = JointDynamics(
                    # (joint.sdf sets no minimum; the simulator treats a negative value as 0)
                    damping=float_value(doc, dyn, "damping", 0.0),
                    friction=float_value(doc, dyn, "friction", 0.0),
                    spring_reference=float_value(doc, dyn, "spring_reference", 0.0),
                    spring_stiffness=float_value(doc, dyn, "spring_stiffness", 0.0),
                )
        axis_model = frame.rotate(xyz)
    mimic_el = child(axis_el, "mimic") if axis_el is not None else None
    mimic = _mimic(b, key, doc, mimic_el) if mimic_el is not None else None
    child_pose_model = g.pose_model(child_link)
    return Joint(
        name=key,
        type=kind,
        parent=parent,
        child=child_link,
        pose_world=model_world.compose(pose_model),
        pose_child=child_pose_model.inverse().compose(pose_model),
        axis_world=model_world.rotate(axis_model) if axis_model else None,
        axis_child=child_pose_model.inverse().rotate(axis_model) if axis_model else None,
        limits=limits,
        dynamics=dynamics,
        mimic=mimic,
    )


MIMIC_JOINT_TYPES = ("revolute", "continuous", "prismatic")


def _mimic(b: _Builder, key: str, doc: Doc, el: Element) -> tuple[str, float, float]:
    """<mimic joint="leader" axis="axis"><multiplier/><offset/><reference/></mimic> (sdformat's mimic.sdf)."""
    g = b.graph
    kind = g.nodes[key].el.get("type")
    if kind not in MIMIC_JOINT_TYPES:
        fail(doc, el, f"a {kind} joint cannot mimic another", hint="valid: " + ", ".join(MIMIC_JOINT_TYPES))
    leader_name = (el.get("joint") or "").strip()
    if not leader_name:
        fail(doc, el, "<mimic> needs a 'joint' attribute naming the joint to follow")
    scope = next(s for k, s in b.joints if k == key)
    leader = scope.lookup(leader_name)
    joints = [k for k, _ in b.joints if k != key]
    if leader is None or g.nodes[leader].kind != "joint":
        fail(
            doc,
            el,
            f"<mimic joint={leader_name!r}> names no joint of this model{suggest(leader_name, joints)}",
            hint="joints: " + ", ".join(joints),
        )
    if leader == key:
        fail(doc, el, f"joint {key!r} cannot mimic itself")
    leader_kind = g.nodes[leader].el.get("type")
    if leader_kind not in MIMIC_JOINT_TYPES:
        fail(
            doc,
            el,
            f"joint {leader!r} is {leader_kind}: it has no axis to mimic",
            hint="mimic a " + ", ".join(MIMIC_JOINT_TYPES) + " joint",
        )
    axis = (el.get("axis") or "axis").strip()
    if axis != "axis":
        fail(doc, el, f"<mimic axis={axis!r}>: joint {leader!r} has a single axis", hint="valid: axis")
    multiplier = float_value(doc, el, "multiplier", 1.0)
    offset = float_value(doc, el, "offset", 0.0)
    reference = float_value(doc, el, "reference", 0.0)
    return (leader, multiplier, offset - multiplier * reference)


def _check_mimic_chains(b: _Builder, joints: tuple[Joint, ...]) -> None:
    """Followers may be led by followers (a chain), never round in a loop: no position would satisfy it."""
    leader_of = {j.name: j.mimic[0] for j in joints if j.mimic is not None}
    for start in leader_of:
        seen = [start]
        joint = leader_of[start]
        while joint in leader_of:
            if joint == start:
                node = b.graph.nodes[start]
                fail(node.doc, node.el, "joints mimic each other in a loop: " + " → ".join([*seen, start]))
            if joint in seen:
                break  # a loop not through `start`: reported when its own member is the start
            seen.append(joint)
            joint = leader_of[joint]


def _limits(doc: Doc, axis_el: Element, kind: str) -> JointLimits:
    lim = child(axis_el, "limit")
    if lim is None:
        return JointLimits()
    lower = float_value(doc, lim, "lower", -1e16, allow_inf=True)
    upper = float_value(doc, lim, "upper", 1e16, allow_inf=True)
    effort = float_value(doc, lim, "effort", -1.0, allow_inf=True)
    velocity = float_value(doc, lim, "velocity", -1.0, allow_inf=True)
    if kind == "continuous":
        lower, upper = -1e16, 1e16  # Gazebo ignores position limits on continuous joints
    # (sdformat and urdfdom keep <lower> above <upper> as written; the simulator then applies no position limit)
    # SDF: a negative effort or velocity limit means "no limit".
    return JointLimits(lower, upper, math.inf if effort < 0 else effort, math.inf if velocity < 0 else velocity)


def _check_tree(b: _Builder, static: bool, links: dict[str, Link]) -> None:
    g = b.graph
    child_of: dict[str, str] = {}
    for key, (_, child_link) in b.joint_refs.items():
        if child_link in child_of:
            node = g.nodes[key]
            fail(
                node.doc,
                node.el,
                f"link {child_link!r} is the child of joints {child_of[child_link]!r} and {key!r}",
                hint="a model's joints must form a tree",
            )
        child_of[child_link] = key
    for key in b.joint_refs:  # walking up from every joint must end at a root, not loop
        seen = set()
        link = b.joint_refs[key][1]
        while link in child_of:
            if link in seen:
                node = g.nodes[key]
                fail(node.doc, node.el, f"joints form a loop through link {link!r}")
            seen.add(link)
            link = b.joint_refs[child_of[link]][0]
    if static:
        return
    # Links welded by fixed joints move as one body: that body needs mass somewhere if it moves at all.
    group_of = {name: name for name in links}

    def find(x: str) -> str:
        while group_of[x] != x:
            x = group_of[x]
        return x

    for key, (parent, child_link) in b.joint_refs.items():
        if g.nodes[key].el.get("type") == "fixed" and parent != "world":
            group_of[find(child_link)] = find(parent)
    has_mass = {find(n) for n, link in links.items() if link.inertial is not None}
    movers = [(n, None) for n in links if n not in child_of]
    movers += [(b.joint_refs[j][1], j) for j in b.joint_refs if g.nodes[j].el.get("type") != "fixed"]
    for name, joint in movers:
        if find(name) not in has_mass and not links[name].kinematic:
            node = g.nodes[name]
            why = f"child of {g.nodes[joint].el.get('type')} joint {joint!r}" if joint else "a free body"
            fail(
                node.doc,
                node.el,
                f"link {name!r} moves ({why}) but neither it nor any link fixed to it has an <inertial>",
                hint="add <inertial><mass>…</mass><inertia>…</inertia></inertial>, or make the model <static>",
            )


def _shapes(doc: Doc, els: list[Element], parse: Callable[..., Any], to_link: ToLink, kind: str) -> tuple[Any, ...]:
    """The link's visuals or collisions; one whose mesh file is missing is left out with an error, as in Gazebo."""
    out = []
    for el in els:
        try:
            out.append(parse(doc, el, to_link))
        except MeshNotFound as e:
            report_missing_mesh(e, kind)
    return tuple(out)


def build_model(
    doc: Doc,
    el: Element,
    *,
    name: str,
    parent_world: Pose,
    static: bool | None,
    stack: tuple[str, ...],
    pose_override: Pose | None = None,
    placement: str | None = None,
    extra_plugins: tuple[tuple[Doc, Element], ...] = (),
) -> Model:
    """`extra_plugins`: the <plugin>s of the <include> that brought the model in (sdformat appends them)."""
    b = _Builder(name)
    top = Scope(prefix="", model_key=MODEL_FRAME)
    b.collect(doc, el, top, stack)
    b.plugins.extend(extra_plugins)
    b.graph.nodes[MODEL_FRAME] = Node(MODEL_FRAME, "model", Pose(), doc, el, attached_to=top.canonical)
    b.resolve(top)
    is_static = static if static is not None else bool_value(doc, el, "static", False)

    pose, _, _ = pose_child(doc, el)
    if pose_override is not None:
        pose = pose_override
    placement = placement or (el.get("placement_frame") or "").strip() or None
    model_world = parent_world.compose(pose)
    if placement is not None:
        key = b.graph.resolve_ref(top, placement, doc, el, "placement_frame")
        model_world = model_world.compose(b.graph.pose_model(key).inverse())

    links: dict[str, Link] = {}
    ignored: list[str] = []
    for key, scope in b.links:
        node = b.graph.nodes[key]
        pm = b.graph.pose_model(key)
        pw = model_world.compose(pm)
        to_link = b.to_link(key, scope, node.doc)
        inertial_el = child(node.el, "inertial")
        sensors: list[Sensor] = []
        for s in children(node.el, "sensor"):
            sensor = parse_sensor(node.doc, s, key, to_link, pw)
            if sensor is None and s.get("type") in ("thermal_camera", "thermal"):
                ignored.append(
                    f"thermal camera {s.get('name')!r} on link {key!r} is not simulated (diffctl renders no"
                    " temperatures): its image topic stays silent"
                )
            elif sensor is None:
                ignored.append(f"sensor {s.get('name')!r} of type {s.get('type')!r} on link {key!r} is not simulated")
            else:
                sensors.append(sensor)
        links[key] = Link(
            name=key,
            pose_world=pw,
            pose_model=pm,
            inertial=parse_inertial(node.doc, inertial_el, to_link) if inertial_el is not None else None,
            collisions=_shapes(node.doc, children(node.el, "collision"), parse_collision, to_link, "collision"),
            visuals=_shapes(node.doc, children(node.el, "visual"), parse_visual, to_link, "visual"),
            sensors=tuple(sensors),
            gravity=bool_value(node.doc, node.el, "gravity", True),
            kinematic=bool_value(node.doc, node.el, "kinematic", False),
            self_collide=bool_value(node.doc, node.el, "self_collide", False),
        )
    joints = tuple(_joint(b, key, model_world) for key, _ in b.joints)
    _check_tree(b, is_static, links)
    _check_mimic_chains(b, joints)
    frames = tuple(
        Frame(key, b.graph.link_of(key), model_world.compose(b.graph.pose_model(key)), b.graph.pose_model(key))
        for key in [k for k, _ in b.frames] + b.models
    )
    plugins: tuple[Plugin, ...] = tuple(parse_plugin(d, p) for d, p in b.plugins)
    controls = tuple(_ros2_control(d, e, joints) for d, e in b.ros2_control)
    return Model(
        name=name,
        static=is_static,
        pose_world=model_world,
        links=tuple(links.values()),
        joints=joints,
        frames=frames,
        plugins=plugins,
        ros2_control=controls,
        canonical_link=top.canonical or "",
        self_collide=bool_value(doc, el, "self_collide", False),
        source=doc.source,
        ignored=tuple(ignored),
    )


def _ros2_control(doc: Doc, el: Element, joints: tuple[Joint, ...]) -> Ros2Control:
    block = parse_ros2_control(el, doc.source)
    names = [j.name for j in joints]
    for j in block.joints:
        if j.name not in names:
            line = next((c.sourceline for c in el.iter("joint") if c.get("name") == j.name), el.sourceline)
            raise DescriptionError(
                f"<ros2_control name={block.name!r}> names joint {j.name!r}, which the model does not have"
                + suggest(j.name, names),
                source=doc.source,
                line=line,
                field="ros2_control/joint",
                hint="joints: " + ", ".join(names),
            )
    return block
