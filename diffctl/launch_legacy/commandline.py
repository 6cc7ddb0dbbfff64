"""A process's final command line: its argv plus, for ROS nodes, the `--ros-args` tail.

Inline parameters are written as ROS parameter files into the run's log directory (a robot_description
SDF is far too long for a command line), exactly as ros2 launch does.
"""

from __future__ import annotations

import re
from pathlib import Path

import yaml

from diffctl.launch_legacy.parameters import CommandLineParameter
from diffctl.launch_legacy.plan import ProcessSpec

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
        if isinstance(entry, CommandLineParameter):
            continue
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


def ros_arguments(spec: ProcessSpec, params_dir: Path = PRINT_PARAMS_DIR, *, write: bool = False) -> list[str]:
    """launch_ros's order: name, namespace, SetParameter/SetParametersFromFile ones, the node's own, remaps."""
    node = spec.node
    if node is None:
        return []
    out: list[str] = []
    if node.node_name:
        out += ["-r", f"__node:={node.node_name}"]
    if node.namespace and (node.namespace != "/" or node.namespace_given):
        out += ["-r", f"__ns:={node.namespace}"]
    for entry in node.global_params:
        if isinstance(entry, tuple):
            out += ["-p", f"{entry[0]}:={entry[1]}"]
        else:
            out += ["--params-file", entry]
    files = iter(params_files(spec, params_dir, write=write))
    for entry in node.params:  # files and `-p` in the order the node's parameters list them, as launch_ros
        if isinstance(entry, CommandLineParameter):
            out += ["-p", f"{entry.name}:={entry.text}"]
        else:
            out += ["--params-file", next(files)]
    for src, dst in node.remaps:
        out += ["-r", f"{src}:={dst}"]
    return ["--ros-args", *out]  # launch_ros gives every node `--ros-args`, even with nothing after it


def argv(spec: ProcessSpec, params_dir: Path = PRINT_PARAMS_DIR, *, write: bool = False) -> list[str]:
    """The command that starts `spec`; with write=True the parameter files are created in params_dir."""
    return list(spec.argv) + ros_arguments(spec, params_dir, write=write)
