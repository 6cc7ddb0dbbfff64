import sys
from pathlib import Path

import lifecycle_msgs.msg
from launch.actions import LogInfo, RegisterEventHandler, Shutdown
from launch_ros.actions import LifecycleNode, LifecycleTransition
from launch_ros.event_handlers import OnStateTransition

from launch import LaunchDescription


def generate_launch_description():
    node = LifecycleNode(
        executable=sys.executable, arguments=[str(Path(__file__).parent / "managed.py")],
        name="managed", namespace="robot", output="screen",
    )
    return LaunchDescription([
        RegisterEventHandler(OnStateTransition(
            target_lifecycle_node=node, start_state="activating", goal_state="active",
            entities=[LogInfo(msg="now active"), Shutdown(reason="managed node is active")])),
        node,
        LifecycleTransition(
            lifecycle_node_names=["robot/managed"],
            transition_ids=[lifecycle_msgs.msg.Transition.TRANSITION_CONFIGURE,
                            lifecycle_msgs.msg.Transition.TRANSITION_ACTIVATE]),
    ])
