"""Controller-manager parameters (`controller_manager.ros__parameters`) validated into `ManagerParams`.

The manager's parameters come, as in ros2_control_node, from its node's arguments: `--params-file`s (the
gz_ros2_control `<parameters>` files become exactly that) and `-p` rules. The manager node declares them
(controller_manager_parameters.yaml's, see manager_node.py); their values are validated once, here, into a
frozen `ManagerParams`, with the per-controller settings (`<name>.type`, `.params_file`,
`.fallback_controllers`, `.node_options_args`). A controller's own parameters are its node's business
(controller_node.py).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from diffctl.errors import ParameterError, suggest
from diffctl.ros_args import ParameterOverrides, node_fqn

STRICTNESS = {"best_effort": 1, "strict": 2, "auto": 3, "force_auto": 4}

# Parameters the manager itself understands; anything else with a dot is a per-controller key.
_MANAGER_KEYS = {
    "update_rate",
    "use_sim_time",
    "enforce_command_limits",
    "handle_exceptions",
    "overruns.manage",
    "defaults.switch_controller.strictness",
    "hardware_components_initial_state.unconfigured",
    "hardware_components_initial_state.inactive",
    "thread_priority",
    "cpu_affinity",
    "lock_memory",
    "robot_description",
}
_CONTROLLER_KEYS = {"type", "params_file", "fallback_controllers", "node_options_args"}


@dataclass(frozen=True)
class ControllerSpec:
    """What the manager node knows about one controller: `<name>.type`, `.params_file`, `.update_rate`…"""

    name: str
    type: str | None = None
    params_files: tuple[str, ...] = ()
    fallback_controllers: tuple[str, ...] = ()
    node_options_args: tuple[str, ...] = ()  # the spawner's --controller-ros-args: the node's remaps, -p values


@dataclass(frozen=True)
class ManagerParams:
    update_rate: int = 100
    use_sim_time: bool = False
    handle_exceptions: bool = True
    enforce_command_limits: bool = False  # joint limits from the robot description bound the commands
    manage_overruns: bool = True
    default_strictness: int = STRICTNESS["best_effort"]
    hardware_unconfigured: tuple[str, ...] = ()
    hardware_inactive: tuple[str, ...] = ()
    thread_priority: int = 50
    controllers: Mapping[str, ControllerSpec] = field(default_factory=dict)
    # The manager node's own arguments (`--ros-args --params-file …`): its controllers' nodes inherit them.
    node_arguments: tuple[str, ...] = ()
    source: str = "controller_manager parameters"

    @property
    def period_s(self) -> float:
        return 1.0 / self.update_rate


def _bool(value: Any, key: str, source: str) -> bool:
    if isinstance(value, bool):
        return value
    # A launch substitution ($(var use_sim_time)) arrives as text; ROS launch types it as YAML does.
    if isinstance(value, str) and value.strip().lower() in ("true", "false"):
        return value.strip().lower() == "true"
    raise ParameterError(f"{value!r} is not a bool (true or false)", source=source, field=key)


def _str_list(value: Any, key: str, source: str) -> tuple[str, ...]:
    if isinstance(value, str):
        return (value,)
    if isinstance(value, list | tuple) and all(isinstance(v, str) for v in value):
        return tuple(value)
    raise ParameterError(f"{value!r} is not a string or a list of strings", source=source, field=key)


def _rate(value: Any, key: str, source: str, *, allow_zero: bool = False) -> int:
    ok = isinstance(value, int) and not isinstance(value, bool)
    if isinstance(value, float) and math.isfinite(value) and value.is_integer():
        value, ok = int(value), True
    if not ok or value < 0 or (value == 0 and not allow_zero) or value > 100_000:
        lo = "≥ 0" if allow_zero else "> 0"
        raise ParameterError(
            f"{value!r} is not a valid rate: an integer in Hz, {lo} and ≤ 100000", source=source, field=key
        )
    return int(value)


def manager_params(
    flat: Mapping[str, Any], *, source: str = "controller_manager parameters", node_arguments: Sequence[str] = (),
) -> ManagerParams:
    """Validate the manager node's flattened parameters into a `ManagerParams` (raises ParameterError)."""
    kw: dict[str, Any] = {}
    specs: dict[str, dict[str, Any]] = {}
    for key, value in flat.items():
        if key == "update_rate":
            kw["update_rate"] = _rate(value, key, source)
        elif key == "use_sim_time":
            kw["use_sim_time"] = _bool(value, key, source)
        elif key == "handle_exceptions":
            kw["handle_exceptions"] = _bool(value, key, source)
        elif key == "enforce_command_limits":
            kw["enforce_command_limits"] = _bool(value, key, source)
        elif key == "overruns.manage":
            kw["manage_overruns"] = _bool(value, key, source)
        elif key == "defaults.switch_controller.strictness":
            if value not in STRICTNESS:
                raise ParameterError(
                    f"{value!r} is not a strictness{suggest(str(value), STRICTNESS)}",
                    source=source,
                    field=key,
                    hint="valid: " + ", ".join(STRICTNESS),
                )
            kw["default_strictness"] = STRICTNESS[value]
        elif key == "thread_priority":
            if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= 99:
                raise ParameterError(
                    f"{value!r} is not a priority (an integer 0..99; 0 disables SCHED_FIFO)", source=source, field=key
                )
            kw["thread_priority"] = value
        elif key == "hardware_components_initial_state.unconfigured":
            kw["hardware_unconfigured"] = _str_list(value, key, source)
        elif key == "hardware_components_initial_state.inactive":
            kw["hardware_inactive"] = _str_list(value, key, source)
        elif key in _MANAGER_KEYS:
            continue
        elif "." in key:
            name, _, sub = key.rpartition(".")
            if sub in _CONTROLLER_KEYS:
                specs.setdefault(name, {})[sub] = value
            # Other dotted keys (a controller's own parameters written under the manager) are left to it.
    controllers = {name: controller_spec(name, d, source) for name, d in specs.items()}
    return ManagerParams(**kw, controllers=controllers, node_arguments=tuple(node_arguments), source=source)


def controller_spec(name: str, d: Mapping[str, Any], source: str) -> ControllerSpec:
    ctype = d.get("type")
    if ctype is not None and (not isinstance(ctype, str) or "/" not in ctype):
        raise ParameterError(
            f"{ctype!r} is not a controller type like 'diff_drive_controller/DiffDriveController'",
            source=source,
            field=f"{name}.type",
        )
    files = _str_list(d["params_file"], f"{name}.params_file", source) if "params_file" in d else ()
    fallbacks = (
        _str_list(d["fallback_controllers"], f"{name}.fallback_controllers", source)
        if "fallback_controllers" in d
        else ()
    )
    options = _str_list(d["node_options_args"], f"{name}.node_options_args", source) if "node_options_args" in d else ()
    return ControllerSpec(name, ctype, files, fallbacks, options)


def with_controller_param(params: ManagerParams, name: str, key: str, value: Any) -> ManagerParams:
    """A copy of `params` with `<name>.<key>` set (the spawner's set_parameters on the manager node)."""
    old = params.controllers.get(name, ControllerSpec(name))
    d: dict[str, Any] = {
        "type": old.type,
        "params_file": list(old.params_files),
        "fallback_controllers": list(old.fallback_controllers),
        "node_options_args": list(old.node_options_args),
    }
    d = {k: v for k, v in d.items() if v not in (None, [])}
    d[key] = value
    controllers = dict(params.controllers)
    controllers[name] = controller_spec(name, d, f"parameter {name}.{key}")
    return ManagerParams(**{**params.__dict__, "controllers": controllers})


def load_manager_files(files: list[str] | tuple[str, ...], node: str = "/controller_manager") -> dict[str, Any]:
    """The manager's flattened parameters from its parameter files, as rcl reads them for the node whose fully
    qualified name is `node` (a bare name is a node at the root)."""
    table = ParameterOverrides()
    for f in files:
        table.add_file(f)
    return table.for_node(node_fqn(node))


def section_type(path: str, name: str, namespace: str = "/", fatal: Any = None) -> str | None:
    """The `type` a parameter file gives controller `name` (what the spawner forwards to the manager), looked up
    as controller_manager's spawner does (get_parameter_from_param_files): under `name`, `/ns/name`,
    `/**/name` or `/**/ns/name`, or inside a `/**` section; a bare `name` while the spawner has a namespace
    is refused with its "Missing namespace" message (`fatal`, a log function)."""
    value = spawner_file_parameter(path, name, namespace, "type", fatal)
    return value if isinstance(value, str) else None


def spawner_file_parameter(path: str, name: str, namespace: str, parameter: str, fatal: Any = None) -> Any:
    from diffctl.ros_args import _read_yaml_file

    if not Path(path).is_file():
        raise ParameterError("parameter file not found", source=path, hint="give an existing YAML file with -p")
    data = _read_yaml_file(path)
    namespaced = f"/{name}" if namespace in ("", "/") else f"{namespace}/{name}"
    wildcard, ros_params = "/**", "ros__parameters"
    found: Any = None
    for key in (name, namespaced, f"{wildcard}/{name}", f"{wildcard}{namespaced}"):
        if key in data:
            if key == name and namespace not in ("", "/"):
                if fatal is not None:
                    fatal(f"Missing namespace : {namespace} or wildcard in parameter file for controller : {name}")
                break
            found = data[key]
        elif isinstance(data.get(wildcard), dict) and key in data[wildcard]:
            found = data[wildcard][key]
        elif isinstance(data.get(wildcard), dict) and ros_params in data[wildcard]:
            found = data[wildcard]
        if found and (not isinstance(found, dict) or ros_params not in found):
            raise ParameterError(f"not a valid ROS parameter file for controller node {namespaced}", source=path,
                                 field=key, hint=f"give the section a {ros_params} map")
        if found and isinstance(found[ros_params], dict) and parameter in found[ros_params]:
            return found[ros_params][parameter]
    return None
