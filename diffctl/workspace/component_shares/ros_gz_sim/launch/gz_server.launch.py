"""ros_gz_sim's gz_server.launch.py for diffctl: the simulator server alone, on a world file or SDF text.

Arguments as in ros_gz_sim (Jazzy): world_sdf_file, world_sdf_string (written to diffctl's cache, never
next to the user's files), start_paused, and the composition arguments container_name,
create_own_container, use_composition (accepted: the simulator is one process). Without a world the
server runs Gazebo's empty.sdf, as `gz sim -s` does.
"""

import hashlib
import os

from launch.actions import AppendEnvironmentVariable, DeclareLaunchArgument, OpaqueFunction
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

from diffctl.errors import LaunchError
from diffctl.workspace.builtin import GAZEBO_WORLDS
from launch import LaunchDescription

TRUE_WORDS, FALSE_WORDS = ("true", "1", "yes", "on"), ("false", "0", "no", "off", "")


def _flag(context, name):
    value = LaunchConfiguration(name).perform(context).strip().lower()
    if value not in TRUE_WORDS + FALSE_WORDS:
        raise LaunchError(
            f"launch argument {name}:={value!r} of gz_server.launch.py is not a boolean", hint="valid: true, false"
        )
    return value in TRUE_WORDS


def _world_from_text(text):
    cache = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    folder = os.path.join(cache, "diffctl", "worlds")
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, hashlib.sha256(text.encode()).hexdigest()[:16] + ".sdf")
    if not os.path.isfile(path):
        with open(path, "w") as f:
            f.write(text)
    return path


def launch_server(context):
    world_file = LaunchConfiguration("world_sdf_file").perform(context).strip()
    world_text = LaunchConfiguration("world_sdf_string").perform(context)
    if world_file and world_text.strip():
        raise LaunchError("gz_server.launch.py: give world_sdf_file or world_sdf_string, not both")
    for name in ("use_composition", "create_own_container"):
        _flag(context, name)
    world = world_file or (_world_from_text(world_text) if world_text.strip() else "empty.sdf")
    arguments = ["-s", world] if _flag(context, "start_paused") else ["-r", "-s", world]
    return [
        AppendEnvironmentVariable("GZ_SIM_RESOURCE_PATH", str(GAZEBO_WORLDS)),
        Node(package="ros_gz_sim", executable="gz_sim", arguments=arguments, output="screen"),
    ]


def generate_launch_description():
    return LaunchDescription(
        [
            DeclareLaunchArgument("world_sdf_file", default_value="", description="Path to the SDF world file"),
            DeclareLaunchArgument("world_sdf_string", default_value="", description="SDF world string"),
            DeclareLaunchArgument("container_name", default_value="ros_gz_container",
                                  description="Accepted for compatibility (composition)"),
            DeclareLaunchArgument("create_own_container", default_value="False",
                                  description="Accepted for compatibility (composition)"),
            DeclareLaunchArgument("use_composition", default_value="False",
                                  description="Accepted for compatibility (composition)"),
            DeclareLaunchArgument("start_paused", default_value="False", description="Start the simulation paused"),
            OpaqueFunction(function=launch_server),
        ]
    )
