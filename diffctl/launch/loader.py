"""Read a launch file with the frontend its name calls for."""

from __future__ import annotations

from pathlib import Path

from diffctl.errors import LaunchError
from diffctl.launch.actions import LaunchDescription


def load(path: str | Path) -> LaunchDescription:
    name = Path(path).name
    if name.endswith(".py"):
        from diffctl.launch import python_frontend

        return python_frontend.load(path)  # type: ignore[return-value]
    if name.endswith((".yaml", ".yml")):
        from diffctl.launch import yaml_frontend

        return yaml_frontend.load(path)
    if name.endswith(".xml"):
        raise LaunchError(
            "XML launch files are not supported", source=str(path), hint="write it in YAML (same tags) or Python"
        )
    raise LaunchError("unknown launch file type", source=str(path), hint="valid: NAME.yaml, NAME.launch.py")
