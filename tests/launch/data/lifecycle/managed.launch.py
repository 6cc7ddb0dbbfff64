import sys
from pathlib import Path

import lifecycle_msgs.msg
from launch.actions import EmitEvent, LogInfo, RegisterEventHandler, Shutdown
from launch.events import matches_action
from launch_ros.actions import LifecycleNode
from launch_ros.event_handlers import OnStateTransition
from launch_ros.events.lifecycle import ChangeState, matches_node_name

from launch import LaunchDescription


def generate_launch_description():
    node = LifecycleNode(
        executable=sys.executable, arguments=[str(Path(__file__).parent / "managed.py")],
        name="managed", namespace="robot", output="screen",
    )
    configure = EmitEvent(event=ChangeState(
        lifecycle_node_matcher=matches_action(node), transition_id=lifecycle_msgs.msg.Transition.TRANSITION_CONFIGURE))
    activate = EmitEvent(event=ChangeState(
        lifecycle_node_matcher=matches_node_name("/robot/managed"),
        transition_id=lifecycle_msgs.msg.Transition.TRANSITION_ACTIVATE))
    return LaunchDescription([
        RegisterEventHandler(OnStateTransition(
            target_lifecycle_node=node, goal_state="inactive",
            entities=[LogInfo(msg="now inactive"), activate])),
        RegisterEventHandler(OnStateTransition(
            target_lifecycle_node=node, start_state="activating", goal_state="active",
            entities=[LogInfo(msg="now active"), Shutdown(reason="managed node is active")])),
        node,
        configure,
    ])
