"""`controller_manager.launch_utils`: launch descriptions that start one spawner for a list of controllers.

Each adds the launch arguments `controller_manager_name` (default controller_manager) and `unload_on_kill`
(default false; "true" passes --unload-on-kill) and a shell-run spawner Node with the controllers, their
--param-file options and the extra spawner arguments, as ros2_control's helpers build them.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from diffctl.launch import LaunchDescription
from diffctl.launch.actions import DeclareLaunchArgument
from diffctl.launch.substitutions import LaunchConfiguration, PythonExpression
from diffctl.launch_ros.actions import Node


def generate_controllers_spawner_launch_description(
    controller_names: list, controller_params_files: Sequence[Any] | None = None, extra_spawner_args: Sequence = ()
) -> LaunchDescription:
    """One spawner loading, configuring and activating `controller_names` (in that order)."""
    arguments: list[Any] = [*controller_names, "--controller-manager", LaunchConfiguration("controller_manager_name")]
    for params_file in controller_params_files or ():
        if params_file:
            arguments += ["--param-file", params_file]
    # an empty word when unload_on_kill is not "true": the shell drops it (launch has no optional argument)
    arguments.append(
        PythonExpression(['"--unload-on-kill" if "', LaunchConfiguration("unload_on_kill"), '" == "true" else ""'])
    )
    arguments += list(extra_spawner_args)
    return LaunchDescription([
        DeclareLaunchArgument(
            "controller_manager_name", default_value="controller_manager",
            description="Controller manager node name"),
        DeclareLaunchArgument(
            "unload_on_kill", default_value="false",
            description="Wait until the node is interrupted and then unload controller"),
        Node(package="controller_manager", executable="spawner", arguments=arguments, shell=True, output="screen"),
    ])  # fmt: skip


def generate_controllers_spawner_launch_description_from_dict(
    controller_info_dict: dict, extra_spawner_args: Sequence = ()
) -> LaunchDescription:
    """`{controller: params file, a list of them, or None}`: the controllers in the dict's order, every file."""
    if type(controller_info_dict) is not dict:
        raise ValueError(f"Invalid controller_info_dict type parsed {controller_info_dict}")
    files: list[Any] = []
    for value in controller_info_dict.values():
        if not value:
            continue
        if type(value) is list:
            files += value
        elif type(value) is str:
            files.append(value)
        else:
            raise ValueError(f"Invalid controller_params_file type parsed in the dict {value}")
    return generate_controllers_spawner_launch_description(
        list(controller_info_dict), controller_params_files=files, extra_spawner_args=extra_spawner_args
    )


def generate_load_controller_launch_description(
    controller_name: str, controller_params_file: Any = None, extra_spawner_args: Sequence = ()
) -> LaunchDescription:
    """One controller, with its parameter file when given."""
    return generate_controllers_spawner_launch_description(
        [controller_name],
        controller_params_files=[controller_params_file] if controller_params_file else None,
        extra_spawner_args=extra_spawner_args,
    )
