"""`diffctl ros2-controllers-test-nodes EXECUTABLE`: the executables of package ros2_controllers_test_nodes."""

from __future__ import annotations

import click


@click.command("ros2-controllers-test-nodes", context_settings={"ignore_unknown_options": True})
@click.argument("executable", type=click.Choice(["publisher_forward_position_controller",
                                                 "publisher_joint_trajectory_controller"]))
def ros2_controllers_test_nodes(executable: str) -> None:
    """Publish a cycle of goals to a forward or joint-trajectory controller.

    \b
    Example:
      diffctl ros2-controllers-test-nodes publisher_forward_position_controller --ros-args \\
          --params-file rrbot_forward_position_publisher.yaml
    """
    from diffctl.ros2_controllers_test_nodes.nodes import run

    raise SystemExit(run(executable))
