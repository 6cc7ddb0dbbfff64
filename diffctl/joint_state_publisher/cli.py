"""`diffctl joint-state-publisher`: the joint_state_publisher executable (package joint_state_publisher)."""

from __future__ import annotations

from pathlib import Path

import click


@click.command("joint-state-publisher")
@click.argument("description_file", required=False, type=click.Path(dir_okay=False, path_type=Path))
def joint_state_publisher(description_file: Path | None) -> int:
    """Publish sensor_msgs/JointState for the non-fixed joints of a robot description (no GUI).

    The description comes from DESCRIPTION_FILE (URDF, SDF or xacro, expanded) and from the latched robot_description
    topic (each message reconfigures). Parameters from --ros-args as the ROS node takes them: rate (Hz,
    default 10), source_list (JointState topics whose values win), zeros.<joint>,
    dependent_joints.<joint>.{parent,factor,offset}, use_mimic_tags, use_smallest_joint_limits,
    publish_default_positions/velocities/efforts, delta, use_sim_time.

    \b
    Example:
      diffctl joint-state-publisher --ros-args -p rate:=20
      diffctl joint-state-publisher robot.urdf --ros-args -p zeros.arm_joint:=0.5
    """
    from diffctl.joint_state_publisher.node import run

    return run(description_file)
