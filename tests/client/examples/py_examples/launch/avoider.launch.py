# ruff: noqa: I001  (written as the ROS 2 examples are)
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        Node(package='py_examples', executable='avoider', output='screen',
             parameters=[{'use_sim_time': True, 'speed': 0.4}]),
    ])
