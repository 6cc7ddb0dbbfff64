from pathlib import Path

from launch.actions import LogInfo, TimerAction
from launch_ros.actions import ComposableNodeContainer, LoadComposableNodes
from launch_ros.descriptions import ComposableNode

from launch import LaunchDescription

HERE = str(Path(__file__).parent)


def generate_launch_description():
    container = ComposableNodeContainer(
        name="my_container", namespace="", package="rclcpp_components", executable="component_container",
        composable_node_descriptions=[
            ComposableNode(package="demo", plugin="talker_component:Talker", name="talker1", namespace="ns",
                           parameters=[{"greeting": "hello"}]),
        ],
        additional_env={"PYTHONPATH": HERE}, output="screen",
    )
    return LaunchDescription([
        container,
        LoadComposableNodes(target_container=container, composable_node_descriptions=[
            ComposableNode(package="demo", plugin="talker_component:Talker", name="talker2"),
        ]),
        TimerAction(period=20.0, actions=[LogInfo(msg="timeout")]),
    ])
