"""teleop_twist_joy's teleop-launch.py: joy_node and teleop_node, configured by config/<joy_config>.config.yaml.

Arguments as upstream's (Jazzy): joy_vel (the topic driven, default cmd_vel), joy_config (ps3, xbox, atk3, xd3,
ps3-holonomic), joy_dev (joy_node's device_id), publish_stamped_twist, config_filepath (overrides joy_config).
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration, TextSubstitution
from launch_ros.actions import Node

from launch import LaunchDescription


def generate_launch_description():
    config_dir = os.path.join(get_package_share_directory("teleop_twist_joy"), "config", "")
    config_filepath = LaunchConfiguration("config_filepath")
    return LaunchDescription([
        DeclareLaunchArgument("joy_vel", default_value="cmd_vel"),
        DeclareLaunchArgument("joy_config", default_value="ps3"),
        DeclareLaunchArgument("joy_dev", default_value="0"),
        DeclareLaunchArgument("publish_stamped_twist", default_value="false"),
        DeclareLaunchArgument("config_filepath", default_value=[
            TextSubstitution(text=config_dir), LaunchConfiguration("joy_config"),
            TextSubstitution(text=".config.yaml")]),
        Node(package="joy", executable="joy_node", name="joy_node",
             parameters=[{"device_id": LaunchConfiguration("joy_dev"), "deadzone": 0.3, "autorepeat_rate": 20.0},
                         config_filepath]),
        Node(package="teleop_twist_joy", executable="teleop_node", name="teleop_twist_joy_node",
             parameters=[config_filepath, {"publish_stamped_twist": LaunchConfiguration("publish_stamped_twist")}],
             remappings={("/cmd_vel", LaunchConfiguration("joy_vel"))}),
    ])
