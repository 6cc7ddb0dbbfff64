"""The tutorial car in the simulator with robot_localization's ekf_node fusing its wheel odometry and IMU, as a
user's launch file composes them (the simulator's own launch file included, the EKF by package name)."""

import os

from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription
from launch.launch_description_sources import AnyLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare

from launch import LaunchDescription


def generate_launch_description():
    sim = IncludeLaunchDescription(
        AnyLaunchDescriptionSource(PathJoinSubstitution([FindPackageShare("diffctl_demo"), "launch",
                                                         "sim_control.yaml"])),
        launch_arguments={"rtf": LaunchConfiguration("rtf"), "viz": LaunchConfiguration("viz")}.items(),
    )
    ekf = Node(
        package="robot_localization", executable="ekf_node", name="ekf_filter_node", output="screen",
        parameters=[os.path.join(os.path.dirname(__file__), "ekf_car.yaml"), {"use_sim_time": True}],
    )
    return LaunchDescription([
        DeclareLaunchArgument("rtf", default_value="1"),
        DeclareLaunchArgument("viz", default_value="false"),
        sim,
        ekf,
    ])
