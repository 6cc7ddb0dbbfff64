"""`diffctl key-teleop`: the executable key_teleop of package key_teleop."""

from __future__ import annotations

import click


@click.command("key-teleop", context_settings={"ignore_unknown_options": True})
def key_teleop() -> None:
    """key_teleop: hold the arrow keys to drive (q quits); velocity on `key_vel` at `hz`.

    \b
    Example:
      diffctl run key_teleop key_teleop --ros-args -r key_vel:=/diffbot_base_controller/cmd_vel
    """
    from diffctl.key_teleop.node import run

    raise SystemExit(run())
