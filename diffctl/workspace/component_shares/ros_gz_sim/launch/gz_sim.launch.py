"""ros_gz_sim's gz_sim.launch.py for diffctl: `gz_args` go to `diffctl sim run`, as they would go to `gz sim`.

Included by launch files written for Gazebo, e.g. the tutorial's
`IncludeLaunchDescription(PythonLaunchDescriptionSource(.../gz_sim.launch.py), launch_arguments={"gz_args": …})`.
Arguments as in ros_gz_sim (Jazzy): gz_args (`-r -s -g -v N`, a world file or a name such as `empty.sdf`),
gz_version, ign_args/ign_version (deprecated spellings), debugger, on_exit_shutdown, and the composition
arguments container_name/create_own_container/use_composition (accepted: the simulator is one process).
`gz sim -g` alone (the GUI client) starts nothing: diffctl's simulator is headless and the browser
visualizer (rviz2) shows the scene. World names are looked up on GZ_SIM_RESOURCE_PATH, which gets the
packages' `gazebo_ros` exports and then Gazebo's own worlds (shipped in this package's worlds/).
"""

import shlex

from launch.actions import AppendEnvironmentVariable, DeclareLaunchArgument, LogInfo, OpaqueFunction, Shutdown
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

from diffctl.errors import LaunchError
from diffctl.sim.cli import parse_gz_args
from diffctl.workspace.builtin import GAZEBO_WORLDS
from diffctl.workspace.gazebo_paths import gazebo_paths
from launch import LaunchDescription

TRUE_WORDS, FALSE_WORDS = ("true", "1", "yes", "on"), ("false", "0", "no", "off", "")


def _flag(context, name):
    value = LaunchConfiguration(name).perform(context).strip().lower()
    if value not in TRUE_WORDS + FALSE_WORDS:
        raise LaunchError(
            f"launch argument {name}:={value!r} of gz_sim.launch.py is not a boolean", hint="valid: true, false"
        )
    return value in TRUE_WORDS


def launch_gz(context):
    gz_args = LaunchConfiguration("gz_args").perform(context)
    ign_args = LaunchConfiguration("ign_args").perform(context)
    actions = []
    if not gz_args.strip() and ign_args.strip():
        actions.append(LogInfo(msg="ign_args is deprecated, migrate to gz_args!"))
        gz_args = ign_args
    version = LaunchConfiguration("ign_version").perform(context) or LaunchConfiguration("gz_version").perform(context)
    if not version.strip().isdigit():
        raise LaunchError(f"launch argument gz_version:={version!r} of gz_sim.launch.py is not a version number")
    try:
        words = shlex.split(gz_args)
    except ValueError as e:
        raise LaunchError(f"launch argument gz_args:={gz_args!r} of gz_sim.launch.py cannot be split: {e}") from None
    # ros_gz_sim tests the text, not its meaning: any non-empty value (its default 'false' too) shuts the
    # launch down when the simulator exits
    shutdown = bool(LaunchConfiguration("on_exit_shutdown").perform(context))
    for name in ("use_composition", "create_own_container"):
        _flag(context, name)
    if LaunchConfiguration("debugger").perform(context) != "false":
        actions.append(
            LogInfo(
                msg="debugger: diffctl's simulator is a Python process; start it under a debugger "
                "with `python -m pdb -m diffctl sim run …` instead"
            )
        )
    parsed = parse_gz_args(words)  # gz sim's option rules: `-rg` and `-g -v4` are the GUI client too
    if parsed.gui_only and not parsed.server_only:
        # `gz sim -g` runs only the GUI client, which connects to a server started elsewhere.
        actions.append(
            LogInfo(
                msg="gz sim -g (GUI client): diffctl's simulator is headless; the browser visualizer shows the scene"
            )
        )
        return actions
    models, plugins = gazebo_paths()
    for path in [*models, str(GAZEBO_WORLDS)]:
        actions.append(AppendEnvironmentVariable("GZ_SIM_RESOURCE_PATH", path))
    for path in plugins:
        actions.append(AppendEnvironmentVariable("GZ_SIM_SYSTEM_PLUGIN_PATH", path))
    extra = {"on_exit": Shutdown()} if shutdown else {}
    actions.append(Node(package="ros_gz_sim", executable="gz_sim", arguments=words, output="screen", **extra))
    return actions


def generate_launch_description():
    return LaunchDescription(
        [
            DeclareLaunchArgument("gz_args", default_value="", description="Arguments for the simulator (gz sim)"),
            DeclareLaunchArgument("gz_version", default_value="8", description="Gazebo Sim's major version"),
            DeclareLaunchArgument("ign_args", default_value="", description="Deprecated: use gz_args"),
            DeclareLaunchArgument("ign_version", default_value="", description="Deprecated: use gz_version"),
            DeclareLaunchArgument("debugger", default_value="false", description="Run in a debugger"),
            DeclareLaunchArgument(
                "on_exit_shutdown", default_value="false", description="Shut the launch down when the simulator exits"
            ),
            DeclareLaunchArgument(
                "container_name",
                default_value="ros_gz_container",
                description="Accepted for compatibility (composition)",
            ),
            DeclareLaunchArgument(
                "create_own_container", default_value="false", description="Accepted for compatibility (composition)"
            ),
            DeclareLaunchArgument(
                "use_composition", default_value="false", description="Accepted for compatibility (composition)"
            ),
            OpaqueFunction(function=launch_gz),
        ]
    )
