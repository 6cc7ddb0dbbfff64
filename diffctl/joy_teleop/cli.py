"""`diffctl joy-teleop`: the executable joy_teleop of package joy_teleop."""

from __future__ import annotations

import click


@click.command("joy-teleop", context_settings={"ignore_unknown_options": True})
def joy_teleop() -> None:
    """Joy messages → the topics, services and actions its parameters configure.

    \b
    Example:
      diffctl joy-teleop --ros-args --params-file joy_teleop.yaml
    """
    from diffctl.joy_teleop.node import run

    raise SystemExit(run())
