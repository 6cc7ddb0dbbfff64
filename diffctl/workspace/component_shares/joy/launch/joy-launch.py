"""joy's joy-launch.py: joy_node with config/joy-params.yaml; the launch shuts down when joy_node exits."""

import os

from ament_index_python.packages import get_package_share_directory
from launch.actions import EmitEvent, RegisterEventHandler
from launch.event_handlers import OnProcessExit
from launch.events import Shutdown
from launch_ros.actions import Node

from launch import LaunchDescription


def generate_launch_description():
    params = os.path.join(get_package_share_directory("joy"), "config", "joy-params.yaml")
    # Upstream's file still says node_executable=, which Jazzy's launch_ros no longer takes.
    joy_node = Node(package="joy", executable="joy_node", output="both", parameters=[params])
    return LaunchDescription([
        joy_node,
        RegisterEventHandler(OnProcessExit(target_action=joy_node, on_exit=[EmitEvent(event=Shutdown())])),
    ])
