"""`diffctl interactive-marker-twist-server`: the executable marker_server of interactive_marker_twist_server."""

from __future__ import annotations

import click


@click.command("interactive-marker-twist-server", context_settings={"ignore_unknown_options": True})
def interactive_marker_twist_server() -> None:
    """marker_server: an interactive marker on the robot; dragging it in RViz sends Twist on `cmd_vel`.

    \b
    Example:
      diffctl run interactive_marker_twist_server marker_server --ros-args \\
          --params-file "$(diffctl pkg prefix interactive_marker_twist_server --share)/config/planar.yaml"
    """
    from diffctl.interactive_marker_twist_server.node import run

    raise SystemExit(run())
