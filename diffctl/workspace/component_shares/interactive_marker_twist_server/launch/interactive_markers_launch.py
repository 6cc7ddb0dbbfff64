"""interactive_marker_twist_server's interactive_markers_launch.py: marker_server with config/<config>.yaml
(`config`: linear, planar or aerial)."""

from launch.actions import DeclareLaunchArgument, SetLaunchConfiguration
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare

from launch import LaunchDescription


def generate_launch_description():
    config_file = PathJoinSubstitution([FindPackageShare("interactive_marker_twist_server"), "config",
                                        LaunchConfiguration("config_file")])
    return LaunchDescription([
        DeclareLaunchArgument("config", default_value="linear"),
        SetLaunchConfiguration("config_file", [LaunchConfiguration("config"), ".yaml"]),
        Node(package="interactive_marker_twist_server", executable="marker_server", name="twist_server_node",
             parameters=[config_file], output="screen"),
    ])
