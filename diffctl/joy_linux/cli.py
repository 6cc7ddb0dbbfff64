"""`diffctl joy-linux joy_linux_node`: the executable joy_linux_node of package joy_linux."""

from __future__ import annotations

import click


@click.group("joy-linux")
def joy_linux() -> None:
    """joy_linux's joy_linux_node: a Linux joystick device (/dev/input/jsX) on `joy` (sensor_msgs/Joy).

    \b
    Example:
      diffctl joy-linux joy_linux_node --ros-args -p dev:=/dev/input/js0
      diffctl run joy_linux joy_linux_node --ros-args -p dev_name:="Microsoft X-Box 360 pad"
    """


@joy_linux.command("joy_linux_node", context_settings={"ignore_unknown_options": True})
def joy_linux_node() -> None:
    """Publish the joystick at `dev` (or the one named `dev_name`) on `joy`; node name joy_node."""
    from diffctl.joy_linux.node import run

    raise SystemExit(run())
