"""`diffctl teleop-twist-joy`: the executable teleop_node of package teleop_twist_joy."""

from __future__ import annotations

import click


@click.command("teleop-twist-joy", context_settings={"ignore_unknown_options": True})
def teleop_twist_joy() -> None:
    """teleop_twist_joy's teleop_node: Joy on `joy` → Twist (or TwistStamped) on `cmd_vel`.

    \b
    Example:
      diffctl run teleop_twist_joy teleop_node --ros-args \\
          --params-file "$(diffctl pkg prefix teleop_twist_joy --share)/config/xbox.config.yaml" \\
          -p publish_stamped_twist:=true -r cmd_vel:=/diffbot_base_controller/cmd_vel
    """
    from diffctl.teleop_twist_joy.node import run

    raise SystemExit(run())
