"""urdf_launch's display.launch.py: description.launch.py, joint_state_publisher(_gui) and rviz2 on config/urdf.rviz.

Arguments as upstream's (Jazzy): urdf_package, urdf_package_path (passed on to description.launch.py),
jsp_gui (true: joint_state_publisher_gui, whose sliders are the visualizer's Joint Sliders panel; false:
joint_state_publisher), rviz_config.
"""

from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription
from launch.conditions import IfCondition, UnlessCondition
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare

from launch import LaunchDescription


def generate_launch_description():
    share = FindPackageShare("urdf_launch")
    gui = LaunchConfiguration("jsp_gui")
    # The included file is handed the two arguments explicitly, as upstream does (ros2/launch#313).
    description = IncludeLaunchDescription(
        PathJoinSubstitution([share, "launch", "description.launch.py"]),
        launch_arguments=[
            ("urdf_package", LaunchConfiguration("urdf_package")),
            ("urdf_package_path", LaunchConfiguration("urdf_package_path")),
        ],
    )
    return LaunchDescription([
        DeclareLaunchArgument("jsp_gui", default_value="true", choices=["true", "false"],
                              description="Flag to enable joint_state_publisher_gui"),
        DeclareLaunchArgument("rviz_config", default_value=PathJoinSubstitution([share, "config", "urdf.rviz"]),
                              description="Absolute path to rviz config file"),
        description,
        Node(package="joint_state_publisher", executable="joint_state_publisher", condition=UnlessCondition(gui)),
        Node(package="joint_state_publisher_gui", executable="joint_state_publisher_gui", condition=IfCondition(gui)),
        Node(package="rviz2", executable="rviz2", output="screen",
             arguments=["-d", LaunchConfiguration("rviz_config")]),
    ])
