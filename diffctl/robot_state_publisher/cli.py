"""`diffctl robot-state-publisher`: the robot_state_publisher executable (package robot_state_publisher)."""

from __future__ import annotations

from pathlib import Path

import click


@click.command("robot-state-publisher")
@click.option(
    "--description",
    "description_file",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="SDF, URDF or xacro file to publish (xacro expanded); overrides the robot_description parameter.",
)
@click.option("--frame-prefix", default=None, help="Prefix for every TF frame name (parameter frame_prefix).")
@click.option(
    "--publish-frequency", type=float, default=None, help="Max /tf rate per joint in Hz (parameter publish_frequency)."
)
@click.option("--use-sim-time", is_flag=True, default=None, help="Stamp with /clock time (parameter use_sim_time).")
def robot_state_publisher(
    description_file: Path | None, frame_prefix: str | None, publish_frequency: float | None, use_sim_time: bool | None
) -> int:
    """Publish /robot_description (latched), /tf_static for fixed joints and /tf from /joint_states.

    Parameters come from --ros-args as for ROS 2's robot_state_publisher (robot_description,
    publish_frequency, frame_prefix, ignore_timestamp, use_sim_time); options given here win.

    \b
    Example:
      diffctl robot-state-publisher --description description/my_diff_car.sdf
      diffctl robot-state-publisher --ros-args -p robot_description:="$(cat description/my_diff_car.sdf)"
    """
    from diffctl.client.parameter import Parameter
    from diffctl.robot_state_publisher.node import run

    options = (("frame_prefix", frame_prefix), ("publish_frequency", publish_frequency),
               ("use_sim_time", use_sim_time))
    return run(description_file, [Parameter(name, value=value) for name, value in options if value is not None])
