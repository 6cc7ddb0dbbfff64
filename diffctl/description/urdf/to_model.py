"""URDF text → the same `model.Model` the SDF loader produces, by way of Gazebo's URDF→SDF conversion.

The generated `<model>` goes through `sdf_model.build_model`, so sensors, plugins, `<ros2_control>` blocks and
every pose are read by the one SDF code path the simulator, robot_state_publisher, the controller manager and
the visualizer already use.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

from lxml import etree

from diffctl.description.model import Link, Mesh, Model
from diffctl.description.pose import Pose
from diffctl.description.resources import search_path_for
from diffctl.description.sdf_model import build_model
from diffctl.description.sdf_values import Doc
from diffctl.description.urdf.parse import parse_urdf
from diffctl.description.urdf.to_sdf import ConversionOptions, urdf_to_sdf

Element = etree._Element


def urdf_model(
    text_or_root: str | Element,
    *,
    source: str = "<string>",
    name: str | None = None,
    pose: Pose | None = None,
    static: bool | None = None,
    base_dir: str | Path | None = None,
    simulation: bool = True,
    check_files: bool = True,
) -> Model:
    """The robot as a Model: Gazebo's lumped view when `simulation`, else every URDF link and joint (for TF)."""
    base = Path(base_dir).resolve() if base_dir is not None else Path.cwd()
    robot = parse_urdf(text_or_root, source)
    options = ConversionOptions(lump=simulation, resolve_meshes=check_files, base_dir=base)
    conv = urdf_to_sdf(robot, options, name)
    # Kinematics need no mass: the tree view skips the simulator's "moving links need an <inertial>" check,
    # and, as urdfdom, every physical check (inertia, a zero joint axis)
    kinematic_only = not simulation and static is None
    doc = Doc(source, base, (1, 11), search_path_for(base), check_files, kinematics_only=kinematic_only)
    model_el = conv.sdf.find("model")
    model = build_model(
        doc,
        model_el,
        name=model_el.get("name"),
        parent_world=Pose(),
        static=True if kinematic_only else static,
        stack=(source,),
        pose_override=pose,
    )
    if kinematic_only:
        declared = (model_el.findtext("static") or "").strip().lower() in ("true", "1")  # <gazebo><static>
        model = dataclasses.replace(model, static=declared)
    if conv.mesh_uris:
        model = dataclasses.replace(model, links=tuple(_with_urdf_uris(link, conv.mesh_uris) for link in model.links))
    return dataclasses.replace(model, ignored=(*conv.ignored, *model.ignored))


def _with_urdf_uris(link: Link, uris: dict[tuple[str, str, int], str]) -> Link:
    """Meshes keep the URI the URDF wrote (package://…) beside the file they load, as SDF meshes do."""

    def fix(geometry: object, kind: str, index: int) -> object:
        uri = uris.get((link.name, kind, index))
        return dataclasses.replace(geometry, uri=uri) if uri is not None and isinstance(geometry, Mesh) else geometry

    return dataclasses.replace(
        link,
        visuals=tuple(
            dataclasses.replace(v, geometry=fix(v.geometry, "visual", i)) for i, v in enumerate(link.visuals)
        ),
        collisions=tuple(
            dataclasses.replace(c, geometry=fix(c.geometry, "collision", i)) for i, c in enumerate(link.collisions)
        ),
    )


def urdf_to_sdf_text(text: str, *, source: str = "<string>", base_dir: str | Path | None = None) -> str:
    """The SDF Gazebo would spawn for this URDF, as text (`gz sdf -p` for diffctl): meshes left as written."""
    base = Path(base_dir).resolve() if base_dir is not None else Path.cwd()
    conv = urdf_to_sdf(parse_urdf(text, source), ConversionOptions(resolve_meshes=False, base_dir=base))
    return etree.tostring(conv.sdf, pretty_print=True, encoding="unicode")
