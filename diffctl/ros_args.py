"""ROS-style `--ros-args` on the command line of every component, as `ros2 launch` passes them.

The launcher writes a node's parameters to a YAML file and starts it with
`--ros-args -r __node:=NAME -r __ns:=/NS --params-file FILE -p name:=value -r from:=to`; components read
them back with `current()`. `diffctl.cli.main` strips the `--ros-args ... [--]` span from argv before
click parses the rest, so every command accepts it without declaring it.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from diffctl.errors import ConfigError, yaml_error

_current: list[str] = []


@dataclass(frozen=True)
class RosArgs:
    node_name: str | None = None
    namespace: str | None = None
    params: dict[str, Any] = field(default_factory=dict)
    remaps: dict[str, str] = field(default_factory=dict)
    params_files: tuple[str, ...] = ()
    log_level: str | None = None

    def param(self, name: str, default: Any = None) -> Any:
        return self.params.get(name, default)


def split_argv(argv: list[str]) -> tuple[list[str], list[str]]:
    """Split argv into (ordinary args, ros args); `--ros-args` spans up to `--` or the end, and may repeat."""
    plain: list[str] = []
    ros: list[str] = []
    i = 0
    while i < len(argv):
        if argv[i] == "--ros-args":
            i += 1
            while i < len(argv) and argv[i] != "--":
                ros.append(argv[i])
                i += 1
            i += 1  # skip the closing "--"
            continue
        plain.append(argv[i])
        i += 1
    return plain, ros


def set_current(ros_argv: list[str]) -> None:
    global _current
    _current = list(ros_argv)


def current_argv() -> list[str]:
    """This process's `--ros-args` as given (for a command that passes them on, as `diffctl run` does)."""
    return list(_current)


def parse_value(text: str) -> Any:
    """A `-p name:=value` value, typed as ROS does (YAML scalar rules: 1 → int, true → bool, [..] → list)."""
    import yaml  # here, not at the top: every `diffctl` command imports this module, most never parse YAML

    try:
        return yaml.safe_load(text) if text != "" else ""
    except yaml.YAMLError:
        return text


def _load_yaml(text: str) -> Any:
    """PyYAML's safe loading on libyaml's parser when PyYAML has it (8× faster on a controllers file: every
    node and controller reads its file at start-up); the error of bad input is the pure-Python parser's, the
    one with the line and column every other file of diffctl reports."""
    import yaml

    loader = getattr(yaml, "CSafeLoader", None)
    if loader is not None:
        try:
            return yaml.load(text, Loader=loader)  # CSafeLoader: the safe loader on libyaml
        except yaml.YAMLError:
            pass
    return yaml.safe_load(text)


def load_params_file(path: str | Path, node_name: str | None) -> dict[str, Any]:
    """Parameters for `node_name` from a ROS params file (`/**`, `name`, `/ns/name` sections, ros__parameters)."""
    import yaml

    p = Path(path)
    try:
        data = _load_yaml(p.read_text()) or {}
    except FileNotFoundError:
        raise ConfigError("parameter file not found", source=str(p)) from None
    except (OSError, UnicodeDecodeError) as e:
        raise ConfigError(f"cannot read the parameter file: {e}", source=str(p)) from None
    except yaml.YAMLError as e:
        raise yaml_error(e, str(p)) from None
    if not isinstance(data, dict):
        raise ConfigError("a parameter file must be a mapping of node names to ros__parameters", source=str(p))
    out: dict[str, Any] = {}
    for key, section in data.items():
        if not isinstance(section, dict) or "ros__parameters" not in section:
            continue
        key = str(key)
        if key in ("/**", "**") or node_name is None or key.lstrip("/").split("/")[-1] == node_name:
            out.update(_flatten(section["ros__parameters"] or {}))
    return out


def _flatten(d: dict[str, Any], prefix: str = "") -> dict[str, Any]:
    # Nested YAML maps become dotted names (linear: {x: {max_velocity: 1}} → linear.x.max_velocity), as rclcpp does.
    out: dict[str, Any] = {}
    for k, v in d.items():
        name = f"{prefix}{k}"
        if isinstance(v, dict):
            out.update(_flatten(v, name + "."))
        else:
            out[name] = v
    return out


def parse(ros_argv: list[str], default_node_name: str | None = None) -> RosArgs:
    node_name = None
    namespace = None
    remaps: dict[str, str] = {}
    inline: dict[str, Any] = {}
    files: list[str] = []
    log_level = None
    i = 0

    def need(flag: str) -> str:
        if i + 1 >= len(ros_argv):
            raise ConfigError(f"--ros-args: {flag} needs a value")
        return ros_argv[i + 1]

    while i < len(ros_argv):
        a = ros_argv[i]
        if a in ("-r", "--remap"):
            rule = need(a)
            if ":=" not in rule:
                raise ConfigError(f"--ros-args: remap {rule!r} must be FROM:=TO")
            src, dst = rule.split(":=", 1)
            if src == "__node" or src == "__name":
                node_name = dst
            elif src == "__ns":
                namespace = dst
            else:
                remaps[src] = dst
            i += 2
        elif a in ("-p", "--param"):
            rule = need(a)
            if ":=" not in rule:
                raise ConfigError(f"--ros-args: parameter {rule!r} must be NAME:=VALUE")
            k, v = rule.split(":=", 1)
            inline[k] = parse_value(v)
            i += 2
        elif a == "--params-file":
            files.append(need(a))
            i += 2
        elif a == "--log-level":
            log_level = need(a)
            i += 2
        elif a in ("-e", "--enclave"):
            i += 2
        else:
            raise ConfigError(
                f"--ros-args: unknown flag {a!r}",
                hint="valid: -r FROM:=TO, -p NAME:=VALUE, --params-file FILE, --log-level LEVEL",
            )
    name = node_name or default_node_name
    params: dict[str, Any] = {}
    for f in files:
        params.update(load_params_file(f, name))
    params.update(inline)
    return RosArgs(name, namespace, params, remaps, tuple(files), log_level)


def current(default_node_name: str | None = None) -> RosArgs:
    """The `--ros-args` this process was started with, parsed for `default_node_name`."""
    return parse(_current, default_node_name)


def build(
    *,
    node_name: str | None = None,
    namespace: str | None = None,
    params_files: list[str] | None = None,
    params: dict[str, Any] | None = None,
    remaps: dict[str, str] | None = None,
) -> list[str]:
    """The `--ros-args …` tail for a command line (empty when there is nothing to pass)."""
    out: list[str] = []
    if node_name:
        out += ["-r", f"__node:={node_name}"]
    if namespace and namespace != "/":
        out += ["-r", f"__ns:={namespace}"]
    for f in params_files or []:
        out += ["--params-file", str(f)]
    import yaml

    for k, v in (params or {}).items():
        out += ["-p", f"{k}:={v if isinstance(v, str) else yaml.safe_dump(v, default_flow_style=True).strip()}"]
    for k, v in (remaps or {}).items():
        out += ["-r", f"{k}:={v}"]
    return ["--ros-args", *out] if out else []
