"""`diffctl twist-mux`: the twist_mux executable of package twist_mux."""

from __future__ import annotations

import click


@click.command("twist-mux", context_settings={"ignore_unknown_options": True})
def twist_mux() -> None:
    """Multiplex velocity commands by priority (topics/locks parameters, as twist_mux's YAML files give them).

    \b
    Example:
      diffctl twist-mux --ros-args --params-file twist_mux_topics.yaml -r cmd_vel_out:=/cmd_vel
    """
    from diffctl.twist_mux.node import run

    raise SystemExit(run())
