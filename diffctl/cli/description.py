"""`diffctl description show FILE`: what the simulator makes of a robot description (`gz sdf -p` for URDF).

A URDF (or a xacro file expanding to one) is printed as the SDF Gazebo's converter would spawn: fixed joints
lumped, `<gazebo>` extensions applied, `<mimic>` as SDF 1.11's `<axis><mimic>`. An SDF file is printed as read
(xacro expanded). Either way the model is then loaded as the simulator loads it, so a description it would
refuse is an error here too, and what it reads but does not simulate is a warning on stderr.
"""

from __future__ import annotations

from pathlib import Path

import click


def _mappings(args: tuple[str, ...]) -> dict[str, str]:
    """xacro's `name:=value` arguments."""
    from diffctl.errors import ConfigError

    out: dict[str, str] = {}
    for arg in args:
        name, sep, value = arg.partition(":=")
        if not sep or not name:
            raise ConfigError(
                f"argument {arg!r} is not a xacro argument", field="ARGS", hint="write name:=value, e.g. use_gpu:=false"
            )
        out[name] = value
    return out


def _indented(xml: str) -> str:
    """The XML re-indented two spaces a level (copied-in blocks keep their own whitespace otherwise)."""
    from lxml import etree

    root = etree.fromstring(xml.encode(), etree.XMLParser(remove_blank_text=True, remove_comments=False))
    etree.indent(root, space="  ")
    return etree.tostring(root, encoding="unicode")


@click.group()
def description() -> None:
    """Inspect robot descriptions (SDF, URDF, xacro) as the simulator reads them.

    \b
    Example:
      diffctl description show robot.urdf.xacro
      diffctl description show robot.urdf.xacro prefix:=left_ --summary
    """


@description.command("show")
@click.argument("file", type=click.Path(dir_okay=False, path_type=Path))
@click.argument("args", nargs=-1)
@click.option("--summary", is_flag=True, help="Print the links and joints the simulator builds instead of the SDF.")
def show(file: Path, args: tuple[str, ...], summary: bool) -> None:
    """Print the SDF the simulator spawns for FILE (URDF, SDF or xacro; ARGS are xacro's name:=value).

    \b
    Example:
      diffctl description show my_robot.urdf > my_robot.sdf
      diffctl description show my_robot.urdf.xacro use_sim:=true
    """
    from diffctl.console import make_console, warn
    from diffctl.description.robot_files import description_format, parse_description, read_description_text
    from diffctl.description.urdf.parse import parse_root
    from diffctl.description.urdf.to_model import urdf_to_sdf_text

    source = str(file)
    text = read_description_text(file, _mappings(args))
    base_dir = file.resolve().parent
    kind = description_format(parse_root(text, source), source)
    # Loaded as the simulator loads it (meshes are not opened: the output names them as written).
    model = parse_description(text, source=source, base_dir=base_dir, simulation=True, check_files=False)
    if summary:
        make_console().print(model)
    else:
        sdf = urdf_to_sdf_text(text, source=source, base_dir=base_dir) if kind == "urdf" else text
        click.echo(_indented(sdf))
    for note in model.ignored:
        warn(note)
