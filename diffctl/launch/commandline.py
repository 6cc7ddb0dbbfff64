"""A process's final command line: its argv plus, for ROS nodes, the `--ros-args` tail.

Inline parameters are written as ROS parameter files into the run's log directory (a robot_description
SDF is far too long for a command line), exactly as ros2 launch does.
"""

from __future__ import annotations

import re
from pathlib import Path

import yaml

from diffctl import ros_args
from diffctl.launch.plan import ProcessSpec

PRINT_PARAMS_DIR = Path("<log-dir>/params")


def file_stem(name: str) -> str:
    """A process name made safe as a file name."""
    return re.sub(r"[^A-Za-z0-9_.-]", "_", name) or "process"


def params_files(spec: ProcessSpec, params_dir: Path, *, write: bool) -> list[str]:
    files: list[str] = []
    if spec.node is None:
        return files
    inline = 0
    for entry in spec.node.params:
        if isinstance(entry, str):
            files.append(entry)
            continue
        inline += 1
        path = params_dir / (f"{file_stem(spec.name)}.yaml" if inline == 1 else f"{file_stem(spec.name)}_{inline}.yaml")
        if write:
            params_dir.mkdir(parents=True, exist_ok=True)
            path.write_text(
                yaml.safe_dump({"/**": {"ros__parameters": dict(entry)}}, sort_keys=False, allow_unicode=True)
            )
        files.append(str(path))
    return files


def argv(spec: ProcessSpec, params_dir: Path = PRINT_PARAMS_DIR, *, write: bool = False) -> list[str]:
    """The command that starts `spec`; with write=True the parameter files are created in params_dir."""
    out = list(spec.argv)
    if spec.node is None:
        return out
    return out + ros_args.build(
        node_name=spec.node.node_name,
        namespace=spec.node.namespace,
        params_files=params_files(spec, params_dir, write=write),
        remaps=dict(spec.node.remaps),
    )
