"""`diffctl control …`: the controller manager process and the `ros2 control` verbs.

The verbs talk to a running manager over its services (`-c` picks which one) and print rich tables;
a refused request exits 1 with the manager's reason, a bad argument exits 2.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import click

from diffctl.control.lifecycle import State
from diffctl.control.switching import BEST_EFFORT, STRICT
from diffctl.errors import ConfigError, RuntimeFailure

_STATE_STYLE = {"active": "green", "inactive": "yellow", "unconfigured": "dim", "finalized": "red"}


def _cm_option(f: Any) -> Any:
    return click.option(
        "-c",
        "--controller-manager",
        "manager",
        default="controller_manager",
        show_default=True,
        help="Name of the controller manager node.",
    )(f)


def _timeout_option(f: Any) -> Any:
    return click.option(
        "--controller-manager-timeout",
        "wait_s",
        type=float,
        default=5.0,
        show_default=True,
        help="Seconds to wait for the manager's services.",
    )(f)


@contextmanager
def _client(manager: str, wait_s: float, service: str) -> Iterator[Any]:
    from diffctl import ros_args
    from diffctl.client.context import get_default_context
    from diffctl.client.node import Node
    from diffctl.control.cm_client import ManagerClient, manager_fqn

    manager_fqn(manager)  # a bad -c is bad input (exit 2), told before the bus is asked anything
    context = get_default_context()
    if not context.ok():
        context.init(["ros2", "--ros-args", *ros_args.current_argv()])
    node = Node(f"_diffctl_control_{os.getpid()}", context=context, start_parameter_services=False)
    cm = ManagerClient(node, manager)
    try:
        cm.wait(service, wait_s) if wait_s > 0 else cm.wait(service, 0.01)
        yield cm
    finally:
        cm.close()
        node.destroy_node()
        context.try_shutdown()


def _styled(state: str) -> Any:
    from diffctl.console import Text

    return Text(state, style=_STATE_STYLE.get(state, ""))


def _print(renderable: Any) -> None:
    from diffctl.console import console

    # Interface names are long: fold them in a narrow terminal rather than cutting them with an ellipsis.
    for col in getattr(renderable, "columns", []):
        col.overflow = "fold"
    console.print(renderable)


@click.group()
def control() -> None:
    """Run the controller manager and talk to it, as `ros2_control_node` and `ros2 control` do.

    \b
    Example:
      diffctl control manager --description description/my_diff_car_control.sdf \\
          --param-file config/diff_drive_controller.yaml
      diffctl control list_controllers
      diffctl control switch_controllers --deactivate diffbot_base_controller --strict
    """


@control.command("manager")
@click.option(
    "--description",
    "description_file",
    type=click.Path(dir_okay=False),
    default=None,
    help="Robot description (SDF, URDF or xacro with a <ros2_control> block); default: /robot_description.",
)
@click.option(
    "--param-file",
    "param_files",
    multiple=True,
    type=click.Path(dir_okay=False),
    metavar="FILE",
    help="Controller manager parameter file (repeatable), added to the description's gz_ros2_control <parameters>.",
)
@click.option(
    "--hardware-plugin",
    default=None,
    metavar="PLUGIN",
    help="Use this hardware plugin for every <ros2_control> block, e.g. mock_components/GenericSystem "
    "to run without a simulator.",
)
@click.option(
    "--hardware-param",
    "hardware_params",
    multiple=True,
    metavar="NAME=VALUE",
    help="Extra hardware <param> (repeatable), e.g. calculate_dynamics=true.",
)
def manager(
    description_file: str | None,
    param_files: tuple[str, ...],
    hardware_plugin: str | None,
    hardware_params: tuple[str, ...],
) -> None:
    """The controller manager (ros2_control_node) for mock or real hardware: hardware from <ros2_control>,
    controllers, services. A simulated robot's manager runs inside `diffctl sim` (gz_ros2_control).

    Accepts --ros-args (-p update_rate:=50, --params-file F, -r __ns:=/robot).

    \b
    Example:
      diffctl control manager                     # description from /robot_description
      diffctl control manager --description description/my_diff_car_control.sdf \\
          --param-file config/diff_drive_controller.yaml \\
          --hardware-plugin mock_components/GenericSystem --hardware-param calculate_dynamics=true \\
          --ros-args -p use_sim_time:=false
    """
    from diffctl.control.ros2_control_node import ManagerOptions, main

    hw: dict[str, str] = {}
    for item in hardware_params:
        if "=" not in item:
            raise ConfigError(f"--hardware-param {item!r} must be NAME=VALUE", hint="e.g. calculate_dynamics=true")
        k, v = item.split("=", 1)
        hw[k.strip()] = v.strip()
    main(ManagerOptions(description_file, list(param_files), hardware_plugin, hw))


@control.command("list_controllers")
@_cm_option
@_timeout_option
@click.option("-v", "--verbose", is_flag=True, help="Also show claimed and required interfaces.")
@click.option("--claimed-interfaces", is_flag=True, help="Show claimed interfaces.")
@click.option("--required-state-interfaces", is_flag=True, help="Show required state interfaces.")
@click.option("--required-command-interfaces", is_flag=True, help="Show required command interfaces.")
def list_controllers(
    manager: str,
    wait_s: float,
    verbose: bool,
    claimed_interfaces: bool,
    required_state_interfaces: bool,
    required_command_interfaces: bool,
) -> None:
    """List loaded controllers: name, type, state (and interfaces with -v).

    \b
    Example:
      diffctl control list_controllers -v
    """
    from diffctl.console import table

    with _client(manager, wait_s, "list_controllers") as cm:
        ctrls = cm.list_controllers()
    cols = ["name", "type", "state", "update rate"]
    extra = [
        ("claimed interfaces", "claimed_interfaces", claimed_interfaces),
        ("required command interfaces", "required_command_interfaces", required_command_interfaces),
        ("required state interfaces", "required_state_interfaces", required_state_interfaces),
    ]
    shown = [(title, attr) for title, attr, flag in extra if flag or verbose]
    rows = [
        [
            c.name,
            c.type,
            _styled(c.state),
            f"{c.update_rate} Hz",
            *["\n".join(getattr(c, attr)) or "-" for _, attr in shown],
        ]
        for c in ctrls
    ]
    _print(table(None, cols + [t for t, _ in shown], rows))


@control.command("list_controller_types")
@_cm_option
@_timeout_option
def list_controller_types(manager: str, wait_s: float) -> None:
    """List the controller types the manager can load (installed plugins).

    \b
    Example:
      diffctl control list_controller_types
    """
    from diffctl.console import table

    with _client(manager, wait_s, "list_controller_types") as cm:
        resp = cm.call("list_controller_types")
    _print(table(None, ["type", "base class"], zip(resp.types, resp.base_classes, strict=False)))


def _flags(it: Any, command: bool) -> str:
    out = "available" if it.is_available else "unavailable"
    if command:
        out += ", claimed" if it.is_claimed else ", unclaimed"
    return out


@control.command("list_hardware_components")
@_cm_option
@_timeout_option
@click.option("-v", "--verbose", is_flag=True, help="Also list each component's interfaces.")
def list_hardware_components(manager: str, wait_s: float, verbose: bool) -> None:
    """List hardware components: name, type, plugin, lifecycle state (and interfaces with -v).

    \b
    Example:
      diffctl control list_hardware_components -v
    """
    from diffctl.console import table

    with _client(manager, wait_s, "list_hardware_components") as cm:
        comps = cm.call("list_hardware_components").component
    cols = ["name", "type", "plugin", "state", "rw rate"] + (
        ["command interfaces", "state interfaces"] if verbose else []
    )
    rows = []
    for c in comps:
        row = [c.name, c.type, c.plugin_name, _styled(c.state.label), f"{c.rw_rate} Hz"]
        if verbose:
            row += [
                "\n".join(f"{i.name} [{i.data_type}] [{_flags(i, True)}]" for i in c.command_interfaces) or "-",
                "\n".join(f"{i.name} [{i.data_type}] [{_flags(i, False)}]" for i in c.state_interfaces) or "-",
            ]
        rows.append(row)
    _print(table(None, cols, rows))


@control.command("list_hardware_interfaces")
@_cm_option
@_timeout_option
@click.option("-v", "--verbose", is_flag=True, help="Also show each interface's data type.")
def list_hardware_interfaces(manager: str, wait_s: float, verbose: bool) -> None:
    """List command and state interfaces with their availability and claims (and data types with -v).

    \b
    Example:
      diffctl control list_hardware_interfaces -v
    """
    from diffctl.console import table

    with _client(manager, wait_s, "list_hardware_interfaces") as cm:
        resp = cm.call("list_hardware_interfaces")
    rows = []
    for kind, items in (("command", resp.command_interfaces), ("state", resp.state_interfaces)):
        for i in items:
            rows.append(
                [
                    i.name,
                    kind,
                    "yes" if i.is_available else "no",
                    ("yes" if i.is_claimed else "no") if kind == "command" else "-",
                    *([i.data_type] if verbose else []),
                ]
            )
    _print(table(None, ["interface", "kind", "available", "claimed", *(["data type"] if verbose else [])], rows))


def _check(ok: bool, what: str, reason: str = "") -> None:
    if not ok:
        raise RuntimeFailure(
            f"{what} failed" + (f": {reason}" if reason else ""),
            hint=None if reason else "the controller manager's log says why",
        )


def _set_state(cm: Any, name: str, target: str, timeout_s: float = 5.0) -> None:
    state = cm.controller_state(name)
    if state is None:
        raise RuntimeFailure(f"controller {name!r} is not loaded")
    if target == "unconfigured":
        if state != "inactive":
            raise RuntimeFailure(f"can not cleanup {name!r} from its current state {state!r} (only from inactive)")
        _check(cm.ok("cleanup_controller", name), f"cleanup of {name!r}")
    elif target == "inactive":
        if state == "unconfigured":
            _check(cm.ok("configure_controller", name), f"configure of {name!r}")
        elif state == "active":
            ok, msg = cm.switch([], [name], BEST_EFFORT, True, timeout_s)
            _check(ok, f"deactivation of {name!r}", msg)
        else:
            raise RuntimeFailure(f"can not set {name!r} inactive from its current state {state!r}")
    elif target == "active":
        if state != "inactive":
            raise RuntimeFailure(f"can not activate {name!r} from its current state {state!r} (only from inactive)")
        ok, msg = cm.switch([name], [], BEST_EFFORT, True, timeout_s)
        _check(ok, f"activation of {name!r}", msg)
    from diffctl.console import info

    info(f"Successfully set {name} to {target}")


@control.command("load_controller")
@click.argument("name")
@click.argument("param_file", required=False, type=click.Path(exists=True, dir_okay=False))
@click.option(
    "--set-state",
    type=click.Choice(["inactive", "active"]),
    default=None,
    help="Configure (inactive) or also activate (active) after loading.",
)
@_cm_option
@_timeout_option
def load_controller(name: str, param_file: str | None, set_state: str | None, manager: str, wait_s: float) -> None:
    """Load a controller (its <name>.type must be known, or given by PARAM_FILE).

    \b
    Example:
      diffctl control load_controller diffbot_base_controller config/diff_drive_controller.yaml --set-state active
    """
    from diffctl.console import info
    from diffctl.control.params import section_type

    with _client(manager, wait_s, "load_controller") as cm:
        if param_file:
            cm.set_controller_params(name, section_type(param_file, name), [os.path.abspath(param_file)])
        _check(cm.ok("load_controller", name), f"loading controller {name!r}")
        info(f"Successfully loaded controller {name}")
        if set_state == "inactive":
            _set_state(cm, name, "inactive")
        elif set_state == "active":
            _set_state(cm, name, "inactive")
            _set_state(cm, name, "active")


@control.command("set_controller_state")
@click.argument("name")
@click.argument("state", type=click.Choice(["unconfigured", "inactive", "active"]))
@_cm_option
@_timeout_option
def set_controller_state(name: str, state: str, manager: str, wait_s: float) -> None:
    """Move a loaded controller to unconfigured (cleanup), inactive (configure/deactivate) or active.

    \b
    Example:
      diffctl control set_controller_state diffbot_base_controller inactive
    """
    with _client(manager, wait_s, "list_controllers") as cm:
        _set_state(cm, name, state)


@control.command("switch_controllers")
@click.option("--activate", multiple=True, metavar="NAME", help="Controller to activate (repeatable).")
@click.option("--deactivate", multiple=True, metavar="NAME", help="Controller to deactivate (repeatable).")
@click.option("--strict", "strictness", flag_value=STRICT, help="Abort the whole switch on any problem.")
@click.option("--best-effort", "strictness", flag_value=BEST_EFFORT, help="Drop entries that can not be switched.")
@click.option("--activate-asap", is_flag=True, help="Switch in the next control cycle.")
@click.option("--switch-timeout", type=float, default=5.0, show_default=True, help="Seconds to wait for the switch.")
@_cm_option
@_timeout_option
def switch_controllers(
    activate: tuple[str, ...],
    deactivate: tuple[str, ...],
    strictness: int | None,
    activate_asap: bool,
    switch_timeout: float,
    manager: str,
    wait_s: float,
) -> None:
    """Activate and deactivate controllers in one cycle; with neither flag the manager's default strictness.

    \b
    Example:
      diffctl control switch_controllers --deactivate diffbot_base_controller --activate my_controller --strict
    """
    from diffctl.console import info

    with _client(manager, wait_s, "switch_controller") as cm:
        ok, msg = cm.switch(list(activate), list(deactivate), strictness or 0, activate_asap, switch_timeout)
    _check(ok, "switching controllers", msg)
    info("Successfully switched controllers" + (f" ({msg})" if msg else ""))


def _simple_verb(verb: str, service: str, what: str, done: str, example: str) -> click.Command:
    @click.command(verb, help=f"{what.capitalize()} a controller.\n\n\b\nExample:\n  {example}")
    @click.argument("name")
    @_cm_option
    @_timeout_option
    def cmd(name: str, manager: str, wait_s: float) -> None:
        from diffctl.console import info

        with _client(manager, wait_s, service) as cm:
            _check(cm.ok(service, name), f"{what} of {name!r}")
        info(f"Successfully {done} controller {name}")

    return cmd


control.add_command(
    _simple_verb(
        "unload_controller",
        "unload_controller",
        "unload",
        "unloaded",
        "diffctl control unload_controller diffbot_base_controller",
    )
)
control.add_command(
    _simple_verb(
        "cleanup_controller",
        "cleanup_controller",
        "cleanup",
        "cleaned up",
        "diffctl control cleanup_controller diffbot_base_controller",
    )
)


@control.command("set_hardware_component_state")
@click.argument("name")
@click.argument("state", type=click.Choice(["unconfigured", "inactive", "active", "finalized"]))
@_cm_option
@_timeout_option
def set_hardware_component_state(name: str, state: str, manager: str, wait_s: float) -> None:
    """Move a hardware component through its lifecycle (controllers using it are deactivated first).

    \b
    Example:
      diffctl control set_hardware_component_state robot inactive
    """
    from diffctl.console import info

    with _client(manager, wait_s, "set_hardware_component_state") as cm:
        ok, reached = cm.set_hardware_state(name, State(state))
    _check(ok, f"setting hardware {name!r} to {state}", f"it is {reached}" if reached else "")
    info(f"Successfully set hardware {name} to {state}")
