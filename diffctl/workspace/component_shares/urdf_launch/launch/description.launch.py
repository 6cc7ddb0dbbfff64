"""urdf_launch's description.launch.py: robot_state_publisher on `xacro <share of urdf_package>/<urdf_package_path>`.

Arguments as upstream's (Jazzy): urdf_package, urdf_package_path, both required.
"""

from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue
from launch_ros.substitutions import FindPackageShare

from launch import LaunchDescription


def generate_launch_description():
    description_file = PathJoinSubstitution(
        [FindPackageShare(LaunchConfiguration("urdf_package")), LaunchConfiguration("urdf_package_path")]
    )
    # value_type=str: a description that happens to parse as YAML must stay the text it is
    description = ParameterValue(Command(["xacro ", description_file]), value_type=str)
    return LaunchDescription([
        DeclareLaunchArgument("urdf_package", description="The package where the robot description is located"),
        DeclareLaunchArgument(
            "urdf_package_path", description="The path to the robot description relative to the package root"
        ),
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": description}]),
    ])
