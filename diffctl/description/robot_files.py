"""One entry point for robot descriptions in any format: SDF, URDF, or xacro that expands to either.

The root element decides (`<sdf>` → the SDF loader, `<robot>` → the URDF converter); a `.xacro` file, or text
using the xacro namespace, is expanded first. `simulation=True` gives what Gazebo would spawn (URDF fixed joints
lumped); `simulation=False` gives every link and joint as written, which is what robot_state_publisher, joint
state tools and the visualizer need. SDF is the same either way.
"""

from __future__ import annotations

from pathlib import Path

from lxml import etree

from diffctl.description import sdf_loader
from diffctl.description.model import Model
from diffctl.description.pose import Pose
from diffctl.description.urdf.parse import parse_root
from diffctl.description.urdf.to_model import urdf_model
from diffctl.description.urdf.xacro_runner import process_xacro, process_xacro_text, uses_xacro
from diffctl.errors import DescriptionError

FORMATS = ("sdf", "urdf")


def description_format(root: etree._Element, source: str) -> str:
    if root.tag == "sdf":
        return "sdf"
    if root.tag == "robot":
        return "urdf"
    raise DescriptionError(
        f"a robot description's root element must be <sdf> or <robot>, got <{root.tag}>",
        source=source,
        line=root.sourceline,
        hint="give an SDF model, a URDF, or a xacro file that expands to one",
    )


def read_description_text(path: str | Path, mappings: dict[str, str] | None = None) -> str:
    """The XML of a description file, xacro expanded (with `mappings` as its name:=value arguments)."""
    p = Path(path)
    if p.suffix == ".xacro":
        return process_xacro(p, mappings)
    try:
        text = p.read_text()
    except OSError as e:
        raise DescriptionError(f"cannot read: {e.strerror}", source=str(p)) from None
    return process_xacro(p, mappings) if uses_xacro(text) else text


def parse_description(
    text: str,
    *,
    source: str = "<string>",
    name: str | None = None,
    pose: Pose | None = None,
    static: bool | None = None,
    base_dir: str | Path | None = None,
    simulation: bool = True,
    check_files: bool = True,
) -> Model:
    """A model from SDF or URDF text (e.g. a /robot_description); relative paths resolve against `base_dir`."""
    if uses_xacro(text):
        text = process_xacro_text(text, base_dir or Path.cwd(), source)
    root = parse_root(text, source)
    if description_format(root, source) == "urdf":
        return urdf_model(
            root,
            source=source,
            name=name,
            pose=pose,
            static=static,
            base_dir=base_dir,
            simulation=simulation,
            check_files=check_files,
        )
    return sdf_loader.parse_model(
        text, source=source, name=name, pose=pose, static=static, base_dir=base_dir, check_files=check_files
    )


def load_description(
    path: str | Path,
    *,
    name: str | None = None,
    pose: Pose | None = None,
    static: bool | None = None,
    simulation: bool = True,
    check_files: bool = True,
    mappings: dict[str, str] | None = None,
) -> Model:
    """The model of an SDF, URDF or xacro file."""
    p = Path(path)
    text = read_description_text(p, mappings)
    root = parse_root(text, str(p))
    if description_format(root, str(p)) == "sdf" and p.suffix != ".xacro" and not uses_xacro(text):
        return sdf_loader.load_model(p, name=name, pose=pose, static=static, check_files=check_files)
    return parse_description(
        text,
        source=str(p),
        name=name,
        pose=pose,
        static=static,
        base_dir=p.resolve().parent,
        simulation=simulation,
        check_files=check_files,
    )
