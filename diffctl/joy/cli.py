"""`diffctl joy joy_node`: the executable joy_node of package joy."""

from __future__ import annotations

import click


@click.group("joy")
def joy() -> None:
    """joy's joy_node: a joystick's axes and buttons on `joy` (sensor_msgs/Joy).

    \b
    Example:
      diffctl joy joy_node --ros-args -p device_id:=0 -p deadzone:=0.1
      SDL_JOYSTICK_DEVICE=/dev/input/js3 diffctl run joy joy_node
    """


@joy.command("joy_node", context_settings={"ignore_unknown_options": True})
def joy_node() -> None:
    """Publish the joystick numbered device_id (or named device_name) on `joy`.

    Devices: the paths in SDL_JOYSTICK_DEVICE, then /dev/input/js0, js1, … (the Linux joystick API).
    """
    from diffctl.joy.node import run

    raise SystemExit(run())
