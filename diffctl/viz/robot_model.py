"""The robot as the page draws it: per link, its visual shapes and where the link sits in the model.

Built from the SDF on /robot_description through the description loader. Link frames normally come from TF
(robot_state_publisher); a link TF does not know yet is placed from the SDF's rest pose relative to a
link or frame TF does know, so the car is drawn whole even before every joint state has arrived.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from diffctl.description import model as sdf
from diffctl.description.pose import Pose
from diffctl.errors import DescriptionError
from diffctl.viz.footprint import Outline, Primitive, outline
from diffctl.viz.transforms import Transform

DEFAULT_RGBA = (0.75, 0.75, 0.78, 1.0)


@dataclass(frozen=True)
class LinkShape:
    link: str
    primitive: Primitive
    pose_link: Transform
    rgba: tuple[float, float, float, float]


@dataclass(frozen=True)
class RobotModel:
    name: str
    shapes: tuple[LinkShape, ...]
    anchors: dict[str, Transform]  # link and frame names → pose in the model frame
    skipped: tuple[str, ...] = ()  # visuals that have no top-down outline (meshes, planes)
    # joints a slider can move, as joint_state_publisher_gui offers them: (name, lower, upper) in rad or m
    movable: tuple[tuple[str, float, float], ...] = ()

    @property
    def links(self) -> list[str]:
        return sorted({s.link for s in self.shapes})

    def place(self, known: dict[str, Transform]) -> dict[str, Transform]:
        """Pose in the fixed frame of every link with shapes, from the frames TF knows (`known`)."""
        anchor = next((a for a in self.anchors if a in known), None)
        placed: dict[str, Transform] = {}
        for link in self.links:
            if link in known:
                placed[link] = known[link]
            elif anchor is not None and link in self.anchors:
                model_in_fixed = known[anchor].compose(self.anchors[anchor].inverse())
                placed[link] = model_in_fixed.compose(self.anchors[link])
        return placed

    def outlines(self, known: dict[str, Transform]) -> list[tuple[LinkShape, Outline]]:
        """Top-down outlines, lowest first so the page can paint in order."""
        placed = self.place(known)
        out = []
        for shape in self.shapes:
            if shape.link in placed:
                o = outline(shape.primitive, placed[shape.link].compose(shape.pose_link))
                if o is not None and o.points_xy_m:
                    out.append((shape, o))
        out.sort(key=lambda so: so[1].top_z_m)
        return out


def _transform(p: Pose) -> Transform:
    return Transform(tuple(p.xyz), tuple(p.quat))  # type: ignore[arg-type]


def _primitive(g: object) -> Primitive | None:
    if isinstance(g, sdf.Box):
        return Primitive("box", size_m=tuple(g.size_m))  # type: ignore[arg-type]
    if isinstance(g, sdf.Cylinder):
        return Primitive("cylinder", radius_m=g.radius_m, length_m=g.length_m)
    if isinstance(g, sdf.Sphere):
        return Primitive("sphere", radius_m=g.radius_m)
    if isinstance(g, sdf.Capsule):
        return Primitive("capsule", radius_m=g.radius_m, length_m=g.length_m)
    return None


def from_model(model: sdf.Model) -> RobotModel:
    shapes: list[LinkShape] = []
    skipped: list[str] = []
    anchors: dict[str, Transform] = {}
    for link in model.links:
        anchors[link.name] = _transform(link.pose_model)
        for v in link.visuals:
            prim = _primitive(v.geometry)
            if prim is None:
                skipped.append(f"{link.name}/{v.name} ({type(v.geometry).__name__.lower()})")
                continue
            shapes.append(LinkShape(link.name, prim, _transform(v.pose_link), v.rgba or DEFAULT_RGBA))
    for fr in model.frames:
        anchors.setdefault(fr.name, _transform(fr.pose_model))
    return RobotModel(model.name, tuple(shapes), anchors, tuple(skipped), _movable(model))


def _movable(model: sdf.Model) -> tuple[tuple[str, float, float], ...]:
    """Non-fixed, non-mimic joints with their slider range (joint_state_publisher_gui: ±π when unlimited)."""
    out = []
    for j in model.joints:
        if j.type not in ("revolute", "continuous", "prismatic") or j.mimic is not None:
            continue
        lower, upper = j.limits.lower, j.limits.upper
        if j.type == "continuous" or not (math.isfinite(lower) and math.isfinite(upper)) or upper - lower > 1e6:
            lower, upper = -math.pi, math.pi
        out.append((j.name, lower, upper))
    return tuple(out)


def parse_description(text: str, source: str = "/robot_description") -> RobotModel:
    """The robot in an SDF or URDF string (a <model>, the first model of a <world>, or a <robot>)."""
    from diffctl.description import sdf_loader
    from diffctl.description.robot_files import parse_description as parse_robot

    # Mesh files may live on another machine: the outline does not need them, so they are not checked.
    if "<world" in text:
        world = sdf_loader.parse_world(text, source=source, check_files=False)
        if not world.models:
            raise DescriptionError("the description holds no <model>", source=source)
        return from_model(world.models[0])
    return from_model(parse_robot(text, source=source, simulation=False, check_files=False))
