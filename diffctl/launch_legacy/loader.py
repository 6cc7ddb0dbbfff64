"""Read a launch file with the frontend its name calls for (as `ros2 launch` and AnyLaunchDescriptionSource do)."""

from __future__ import annotations

from pathlib import Path

from diffctl.errors import LaunchError
from diffctl.launch_legacy.actions import LaunchDescription

XML_SUFFIXES = (".xml", ".launch")
YAML_SUFFIXES = (".yaml", ".yml")


def load(path: str | Path) -> LaunchDescription:
    name = Path(path).name
    if name.endswith(".py"):
        from diffctl.launch_legacy import python_frontend

        return python_frontend.load(path)  # type: ignore[return-value]
    if name.endswith(YAML_SUFFIXES):
        from diffctl.launch_legacy import yaml_frontend

        return yaml_frontend.load(path)
    if name.endswith(XML_SUFFIXES):
        from diffctl.launch_legacy import xml_frontend

        return xml_frontend.load(path)
    raise LaunchError(
        "unknown launch file type", source=str(path), hint="valid: NAME.launch.py, NAME.launch.xml, NAME.launch.yaml"
    )
