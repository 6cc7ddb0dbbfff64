"""ros_gz_sim's gz_spawn_model.launch.py for diffctl: one `create` with its arguments as node parameters.

Arguments as in ros_gz_sim: world, file, string, topic, entity_name, allow_renaming, and the pose
x, y, z, R, P, Y (default 0). `create` reads the parameters with its usual precedence.
"""

from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

from launch import LaunchDescription


def generate_launch_description():
    text_arguments = {
        "world": "World name (default: the only world running)",
        "file": "SDF or URDF file, model folder or model:// URI",
        "string": "The model's XML text",
        "topic": "Latched topic with the model's XML",
        "entity_name": "Name of the entity",
    }
    pose = ("x", "y", "z", "R", "P", "Y")
    parameters = {name: LaunchConfiguration(name) for name in ("world", "file", "string", "topic")}
    parameters["name"] = LaunchConfiguration("entity_name")
    parameters["allow_renaming"] = LaunchConfiguration("allow_renaming")
    parameters.update({axis: LaunchConfiguration(axis, default="0.0") for axis in pose})
    return LaunchDescription(
        [
            *(DeclareLaunchArgument(name, default_value="", description=text) for name, text in text_arguments.items()),
            DeclareLaunchArgument(
                "allow_renaming", default_value="False", description="Rename the entity when its name is taken"
            ),
            Node(package="ros_gz_sim", executable="create", output="screen", parameters=[parameters]),
        ]
    )
