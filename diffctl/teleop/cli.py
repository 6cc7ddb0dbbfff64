"""`diffctl teleop keyboard|joy`: teleop_twist_keyboard and joy + teleop_twist_joy in one process each.

Both default to our stack's controller (`/diffbot_base_controller/cmd_vel`, TwistStamped). Started from a
launch file as the ROS nodes (with `--ros-args`), they keep the ROS defaults: a `cmd_vel` remap picks the
topic, `publish_stamped_twist` / `stamped` pick the type.
"""

from __future__ import annotations

import sys
import threading
from dataclasses import dataclass
from typing import Any

import click

from diffctl import ros_args
from diffctl.errors import ConfigError, ParameterError
from diffctl.teleop.joy_config import JoyParams

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


@dataclass(frozen=True)
class JoySettings:
    params: JoyParams
    preset: str | None
    topic: str
    device: str | None
    device_id: int


def joy_settings(
    ra: ros_args.RosArgs, joy_config: str | None, topic: str | None, stamped: bool | None, deadzone: float | None
) -> JoySettings:
    """Everything `teleop joy` needs, from (lowest first) preset, config_filepath, --ros-args, CLI options."""
    params: dict[str, Any] = {}
    config_file = ra.params.get("config_filepath")
    if config_file:
        params.update(ros_args.load_params_file(str(config_file), ra.node_name or JOY_NODE))
    params.update(ra.params)
    preset = joy_config or params.get("joy_config") or (None if config_file else "ps3")
    # Our stack's controller takes TwistStamped; a launch file passes teleop_twist_joy's own default (false).
    params["publish_stamped_twist"] = _flag(params, "publish_stamped_twist", stamped, True)
    if deadzone is not None:
        params["deadzone"] = deadzone
    jp = JoyParams.from_params(params, preset)
    device_id = params.get("device_id", 0)
    if isinstance(device_id, bool) or not str(device_id).strip().isdigit():
        raise ParameterError(f"{device_id!r} invalid; valid: an integer >= 0", field="device_id")
    device = params.get("dev") or params.get("device_name") or None
    return JoySettings(
        jp, preset, choose_topic(topic, ra.remaps), str(device) if device else None, int(str(device_id).strip())
    )


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


@teleop.command("joy")
@click.option(
    "--device",
    "-d",
    default=None,
    help="/dev/input/eventN, or part of the device's name. Default: game pad number device_id (0).",
)
@click.option(
    "--joy-config",
    type=click.Choice(["xbox", "ps3", "atk3"]),
    default=None,
    help="Button/axis preset, as teleop_twist_joy's joy_config (default ps3).",
)
@click.option("--topic", default=None, help=f"Topic to publish on. Default: {DEFAULT_TOPIC}.")
@click.option(
    "--stamped/--unstamped",
    default=None,
    help="TwistStamped (default) or Twist; the parameter is publish_stamped_twist.",
)
@click.option("--deadzone", type=float, default=None, help="Stick deadzone, 0..0.99 (default 0.3).")
@click.option("--list", "list_only", is_flag=True, help="List input devices and exit.")
def joy(
    device: str | None,
    joy_config: str | None,
    topic: str | None,
    stamped: bool | None,
    deadzone: float | None,
    list_only: bool,
) -> None:
    """Drive with a game pad read from Linux evdev, as joy + teleop_twist_joy.

    Hold the enable button (xbox LB, ps3 L2, atk3 trigger) and move the left stick; the turbo button
    (RB, L1, thumb) drives with the turbo scales. Releasing sends one zero command. Every
    teleop_twist_joy parameter is accepted with --ros-args -p NAME:=VALUE (axis_linear.x, scale_linear.x,
    scale_linear_turbo.x, axis_angular.yaw, scale_angular.yaw, enable_button, enable_turbo_button,
    require_enable_button, inverted_reverse, publish_stamped_twist, frame) plus joy's deadzone and
    autorepeat_rate; buttons and axes by name (LB, LEFTY) or SDL index.

    \b
    Example:
      diffctl teleop joy --joy-config xbox
      diffctl teleop joy --device /dev/input/event5 --ros-args -p scale_linear.x:=0.3
      diffctl teleop joy --list
    """
    from diffctl.teleop import evdev_reader

    if list_only:
        from diffctl.console import console, info

        devices = evdev_reader.list_devices()
        if devices:
            console.print(evdev_reader.devices_table(devices))
        else:
            info(evdev_reader.present(devices))
        return
    settings = joy_settings(ros_args.current(JOY_NODE), joy_config, topic, stamped, deadzone)
    jp, preset = settings.params, settings.preset
    path = evdev_reader.find_device(device or settings.device, settings.device_id)
    source = evdev_reader.InputDevice(path)

    from diffctl.teleop.joy import run_joy
    from diffctl.teleop.shutdown import stop_on_signals
    from diffctl.teleop.twist_command import TwistCommand

    try:
        started = _start_node(JOY_NODE, {"publish_stamped_twist": jp.publish_stamped_twist, "frame": jp.frame})
        try:
            command = TwistCommand(started.node, settings.topic, stamped=jp.publish_stamped_twist, frame_id=jp.frame)
            log = started.node.get_logger()
            log.info(
                f"reading {path} '{source.info.name}' (joy_config {preset or 'from file'}), "
                f"publishing {command.typename} on {command.topic}"
            )
            stop = threading.Event()
            stop_on_signals(stop)
            run_joy(source, jp, command, stop, log)
        finally:
            started.stop()
    finally:
        source.close()
