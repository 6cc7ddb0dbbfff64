"""`diffctl twist-stamper twist_stamper|twist_unstamper`: the executables of package twist_stamper."""

from __future__ import annotations

import click


def _run(name: str) -> int:
    from diffctl.twist_stamper.node import run

    return run(name)


@click.group("twist-stamper")
def twist_stamper() -> None:
    """Twist ↔ TwistStamped on cmd_vel_in → cmd_vel_out.

    \b
    Example:
      diffctl twist-stamper twist_stamper --ros-args -r cmd_vel_in:=/cmd_vel \\
          -r cmd_vel_out:=/diffbot_base_controller/cmd_vel -p frame_id:=base_link
    """


@twist_stamper.command("twist_stamper", context_settings={"ignore_unknown_options": True})
def stamp() -> None:
    """Twist on cmd_vel_in → TwistStamped on cmd_vel_out (stamped now, frame_id from the parameter)."""
    raise SystemExit(_run("twist_stamper"))


@twist_stamper.command("twist_unstamper", context_settings={"ignore_unknown_options": True})
def unstamp() -> None:
    """TwistStamped on cmd_vel_in → Twist on cmd_vel_out."""
    raise SystemExit(_run("twist_unstamper"))
