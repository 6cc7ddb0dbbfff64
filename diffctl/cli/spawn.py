"""`diffctl spawn entity|controller`: the ros_gz_sim `create` and controller_manager `spawner` counterparts."""

from __future__ import annotations

import click

from diffctl.cli.lazy import LazyGroup


@click.group(
    cls=LazyGroup,
    lazy_commands={
        "entity": ("diffctl.sim.spawn_entity:spawn_entity", "Spawn a model into the simulator (ros_gz_sim create)."),
        "controller": (
            "diffctl.control.spawner:spawn_controller",
            "Load, configure and activate controllers (controller_manager spawner).",
        ),
    },
)
def spawn() -> None:
    """Spawn a model into the simulator or a controller into the controller manager.

    \b
    Example:
      diffctl spawn entity --name robot --topic /robot_description
      diffctl spawn controller diffbot_base_controller --param-file config/diff_drive_controller.yaml
    """
