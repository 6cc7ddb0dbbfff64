"""`diffctl teleop keyboard|joy`: teleop_twist_keyboard, and joy + teleop_twist_joy in one process.

Both default to our stack's controller (`/diffbot_base_controller/cmd_vel`, TwistStamped). The keyboard one is
teleop_twist_keyboard's executable too (with `--ros-args` it keeps the ROS defaults: a `cmd_vel` remap picks the
topic, `stamped` the type); a launch file's joy, joy_linux and teleop_twist_joy nodes are their own packages.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import click

from diffctl import ros_args
from diffctl.errors import ConfigError, ParameterError

DEFAULT_TOPIC = "/diffbot_base_controller/cmd_vel"
KEYBOARD_NODE = "teleop_twist_keyboard"
JOY_NODE = "teleop_twist_joy_node"


def choose_topic(explicit: str | None, remaps: dict[str, str]) -> str:
    """--topic, else `cmd_vel` when --ros-args remaps it (the ROS nodes' topic), else our controller's topic."""
    if explicit:
        return explicit
    if any(k.lstrip("/") == "cmd_vel" for k in remaps):
        return "cmd_vel"
    return DEFAULT_TOPIC


def _flag(params: dict[str, Any], name: str, cli_value: bool | None, default: bool) -> bool:
    value = cli_value if cli_value is not None else params.get(name, default)
    if isinstance(value, str) and value.lower() in ("true", "false"):
        value = value.lower() == "true"
    if not isinstance(value, bool):
        raise ParameterError(f"{value!r} invalid; valid: true, false", field=name)
    return value


def _start_node(name: str, declared: dict[str, Any]) -> Any:
    """The teleop's client node, spinning on its own thread; `declared` are the parameters it runs with."""
    from diffctl.client import component
    from diffctl.client.node import Node
    from diffctl.client.parameter import Parameter

    def make() -> Any:
        node = Node(name, parameter_overrides=[Parameter(k, value=v) for k, v in declared.items()])
        for k, v in declared.items():
            node.declare_parameter(k, v)
        return node

    return component.start(make)


@click.group("teleop", context_settings={"help_option_names": ["-h", "--help"]})
def teleop() -> None:
    """Drive the robot from a keyboard (teleop_twist_keyboard) or a game pad (joy + teleop_twist_joy).

    \b
    Example:
      diffctl teleop keyboard
      diffctl teleop joy --joy-config xbox
    """


@teleop.command("keyboard")
@click.option("--topic", default=None, help=f"Topic to publish on. Default: {DEFAULT_TOPIC}.")
@click.option(
    "--stamped/--unstamped", default=None, help="TwistStamped (default; what diff_drive_controller takes) or Twist."
)
@click.option("--speed", type=float, default=None, help="Initial linear speed in m/s (default 0.5).")
@click.option("--turn", type=float, default=None, help="Initial angular speed in rad/s (default 1.0).")
@click.option("--speed-limit", type=float, default=None, help="Cap for q/w speed-ups in m/s (default 5.0).")
@click.option("--turn-limit", type=float, default=None, help="Cap for q/e speed-ups in rad/s (default 10.0).")
@click.option("--frame-id", default=None, help="header.frame_id of stamped commands (default empty).")
@click.option(
    "--repeat-rate",
    type=float,
    default=None,
    help="Re-publish a moving command at this rate in Hz, so a cmd_vel_timeout does not stop "
    "the robot between key repeats (default 10; 0 = only on key presses, as upstream).",
)
def keyboard(
    topic: str | None,
    stamped: bool | None,
    speed: float | None,
    turn: float | None,
    speed_limit: float | None,
    turn_limit: float | None,
    frame_id: str | None,
    repeat_rate: float | None,
) -> None:
    """Drive with teleop_twist_keyboard's keys: u i o / j k l / m , . (shift: strafe), q/z w/x e/c speeds.

    Publishes on every key press and sends a zero command on exit (Ctrl-C).

    \b
    Example:
      diffctl teleop keyboard
      diffctl teleop keyboard --unstamped --topic /cmd_vel --speed 0.3
    """
    from diffctl.teleop.keyboard_bindings import KeyboardParams, KeyboardTeleop

    ra = ros_args.current(KEYBOARD_NODE)
    p = ra.params

    def pick(cli: Any, name: str, default: Any) -> Any:
        return cli if cli is not None else p.get(name, default)

    params = KeyboardParams(
        speed_m_s=pick(speed, "speed", 0.5),
        turn_rad_s=pick(turn, "turn", 1.0),
        speed_limit_m_s=pick(speed_limit, "speed_limit", 5.0),
        turn_limit_rad_s=pick(turn_limit, "turn_limit", 10.0),
    )
    is_stamped = _flag(p, "stamped", stamped, True)
    frame = pick(frame_id, "frame_id", "")
    rate = pick(repeat_rate, "repeat_rate", 10.0)
    if isinstance(rate, bool) or not isinstance(rate, (int, float)) or not 0 <= rate <= 1000:
        raise ParameterError(f"{rate!r} invalid; valid: 0 to 1000 Hz", field="repeat_rate")
    if not sys.stdin.isatty():
        raise ConfigError(
            "keyboard teleop reads keys from a terminal, and stdin is not one",
            hint="run it in a terminal (or use `diffctl topic pub` from scripts)",
        )

    from diffctl.teleop.keyboard import run_keyboard
    from diffctl.teleop.twist_command import TwistCommand

    started = _start_node(KEYBOARD_NODE, {"stamped": is_stamped, "frame_id": str(frame)})
    try:
        command = TwistCommand(started.node, choose_topic(topic, ra.remaps), stamped=is_stamped, frame_id=str(frame))
        run_keyboard(
            KeyboardTeleop(params), command, repeat_rate_hz=float(rate), fd_in=sys.stdin.fileno(), out=sys.stdout
        )
    finally:
        started.stop()


@click.command("teleop-twist-keyboard", context_settings={"ignore_unknown_options": True})
def teleop_twist_keyboard() -> None:
    """teleop_twist_keyboard's executable as Jazzy has it: Twist (or TwistStamped) on `cmd_vel` on every key.

    Its parameters, read-only: stamped (false), frame_id ('', only with stamped), speed (0.5), turn (1.0).
    `diffctl teleop keyboard` is the same keys with our controller's topic and TwistStamped as defaults.

    \b
    Example:
      diffctl run teleop_twist_keyboard teleop_twist_keyboard --ros-args -r cmd_vel:=my_cmd_vel
    """
    import math

    from diffctl.client import component
    from diffctl.client.node import Node
    from diffctl.interfaces import get_interface
    from diffctl.teleop.keyboard import run_keyboard
    from diffctl.teleop.keyboard_bindings import KeyboardParams, KeyboardTeleop
    from diffctl.teleop.twist_command import TwistCommand

    if not sys.stdin.isatty():
        raise ConfigError("teleop_twist_keyboard reads keys from a terminal, and stdin is not one",
                          hint="run it in a terminal; in a launch file give its Node a terminal (prefix='xterm -e')")

    def make() -> Any:
        node = Node(KEYBOARD_NODE)
        descriptor = get_interface("rcl_interfaces/msg/ParameterDescriptor")
        for name, default in (("stamped", False), ("frame_id", ""), ("speed", 0.5), ("turn", 1.0)):
            node.declare_parameter(name, default, descriptor(read_only=True))
        if node.get_parameter("frame_id").value and not node.get_parameter("stamped").value:
            raise ConfigError("'frame_id' can only be set when 'stamped' is True", field="frame_id")
        return node

    started = component.start(make)
    try:
        value = started.node.get_parameter
        keys = KeyboardTeleop(KeyboardParams(float(value("speed").value), float(value("turn").value),
                                             math.inf, math.inf))
        command = TwistCommand(started.node, "cmd_vel", stamped=bool(value("stamped").value),
                               frame_id=str(value("frame_id").value))
        run_keyboard(keys, command, repeat_rate_hz=0.0, fd_in=sys.stdin.fileno(), out=sys.stdout)
    finally:
        started.stop()


JOY_CONFIGS = ("ps3", "xbox", "atk3", "xd3", "ps3-holonomic")


def joy_config_file(name: str) -> Path:
    from diffctl.workspace.package_index import share_dir

    return share_dir("teleop_twist_joy") / "config" / f"{name}.config.yaml"


def list_joysticks() -> list[tuple[int, str, str, str]]:
    """(device_id, path, name, axes/buttons) of each joystick joy_node would number."""
    from diffctl.joy.linux_joystick import Joystick
    from diffctl.joy.node import candidates

    rows = []
    for number, path in enumerate(candidates()):
        try:
            device = Joystick(path)
        except OSError as e:
            rows.append((number, path, f"({e.strerror})", ""))
            continue
        ident = device.identity
        device.close()
        counts = f"{ident.axes} axes, {ident.buttons} buttons" if ident.axes is not None else ""
        rows.append((number, path, ident.name or "Unknown", counts))
    return rows


@teleop.command("joy")
@click.option("--device", "-d", default=None,
              help="A joystick device (/dev/input/jsN, or any file of js_event records) or a joystick's name. "
              "Default: joystick number device_id (0).")
@click.option("--joy-config", type=click.Choice(JOY_CONFIGS), default="ps3", show_default=True,
              help="teleop_twist_joy's preset (config/<name>.config.yaml).")
@click.option("--topic", default=None, help=f"Topic to publish on. Default: {DEFAULT_TOPIC}.")
@click.option("--stamped/--unstamped", default=True,
              help="TwistStamped (default; what diff_drive_controller takes) or Twist: publish_stamped_twist.")
@click.option("--deadzone", type=float, default=0.3, show_default=True, help="joy_node's deadzone, 0..1.")
@click.option("--list", "list_only", is_flag=True, help="List the joysticks, numbered as device_id, and exit.")
def joy(device: str | None, joy_config: str, topic: str | None, stamped: bool, deadzone: float,
        list_only: bool) -> None:
    """Drive with a joystick: joy's joy_node and teleop_twist_joy's teleop_node in one process.

    The nodes are upstream's (their parameters, `joy` between them); this command gives them what
    teleop-launch.py gives them, with our controller's topic and TwistStamped as defaults. Hold the preset's
    enable button and move the stick (xbox: button 2 and the left stick). --ros-args -p NAME:=VALUE reaches
    both nodes (scale_linear.x, enable_button, device_id, autorepeat_rate, …).

    \b
    Example:
      diffctl teleop joy --joy-config xbox
      diffctl teleop joy --device /dev/input/js1 --ros-args -p scale_linear.x:=0.3
      diffctl teleop joy --list
    """
    import os

    from diffctl.joy import node as joy_node

    if list_only:
        from diffctl.console import info, table

        rows = list_joysticks()
        if rows:
            from diffctl.console import console

            console.print(table("joysticks", ["device_id", "device", "name", ""], rows))
        else:
            info("no joysticks: /dev/input/js* has none (the joydev module makes them), SDL_JOYSTICK_DEVICE is unset")
        return
    if not 0.0 <= deadzone <= 1.0:
        raise ParameterError(f"{deadzone!r} invalid; valid: 0 to 1", field="deadzone")
    joy_params: dict[str, Any] = {"deadzone": deadzone, "autorepeat_rate": 20.0}
    if device and "/" in device:
        # As SDL does with SDL_JOYSTICK_DEVICE: the listed devices are numbered first.
        listed = os.environ.get(joy_node.DEVICE_LIST_ENV)
        os.environ[joy_node.DEVICE_LIST_ENV] = device + (f":{listed}" if listed else "")
        joy_params["device_id"] = 0
    elif device:
        joy_params["device_name"] = device
    global_params = ros_args.current(JOY_NODE).params
    teleop_params = {**ros_args.load_params_file(joy_config_file(joy_config), JOY_NODE), **global_params,
                     "publish_stamped_twist": stamped}
    run_joy_teleop({**joy_params, **global_params}, teleop_params, topic or DEFAULT_TOPIC)


def run_joy_teleop(joy_params: dict[str, Any], teleop_params: dict[str, Any], topic: str) -> int:
    from diffctl.client import component
    from diffctl.client.executors import SingleThreadedExecutor
    from diffctl.client.node import Node
    from diffctl.client.parameter import Parameter
    from diffctl.joy import node as joy_node
    from diffctl.teleop_twist_joy.node import attach

    component.init()  # an executor belongs to an initialised context
    executor = SingleThreadedExecutor()

    def make() -> Any:
        joy = Node(joy_node.NODE_NAME, client_library="rclcpp",
                   parameter_overrides=[Parameter(k, value=v) for k, v in joy_params.items()])
        joy_node.JoyReader(joy, *joy_node.declare(joy))
        executor.add_node(joy)
        teleop = Node(JOY_NODE, client_library="rclcpp", cli_args=["--ros-args", "-r", f"cmd_vel:={topic}"],
                      parameter_overrides=[Parameter(k, value=v) for k, v in teleop_params.items()])
        attach(teleop)
        return teleop

    return component.run(make, executor=executor)
