"""`diffctl component-container`: Python composable nodes in one process (rclcpp_components' component_container).

The launch gives the nodes as `--nodes JSON` (diffctl/launch_legacy/composable.py): each a plugin (`module:Class` or
an `rclpy_components` entry point name) and its `--ros-args` (name, namespace, parameters, remappings). Each
class is built with `cli_args=` (a component takes `**kwargs` and passes them to rclpy's Node, as ROS's
Python composition expects); all spin in one executor, beside the container's own node.
"""

from __future__ import annotations

import importlib
import json
import sys
from typing import Any

import click

from diffctl.errors import LaunchError


def load_class(plugin: str) -> Any:
    from importlib.metadata import entry_points

    for ep in entry_points(group="rclpy_components"):
        if ep.name == plugin:
            return ep.load()
    module, _, attr = plugin.partition(":")
    if not attr or "::" in plugin:
        raise LaunchError(f"component {plugin!r} is not a Python component (C++ components cannot be loaded)")
    return getattr(importlib.import_module(module), attr)


@click.command("component-container", context_settings={"ignore_unknown_options": True})
@click.option("--nodes", "nodes_json", default="[]", help="The composable nodes to load, as JSON.")
@click.option("--multi-threaded", is_flag=True, help="A multi-threaded executor (component_container_mt).")
@click.argument("ros_args", nargs=-1, type=click.UNPROCESSED)
def component_container(nodes_json: str, multi_threaded: bool, ros_args: tuple[str, ...]) -> None:
    """Host Python composable nodes in one process (ros2 run rclcpp_components component_container)."""
    import rclpy
    from rclpy.executors import ExternalShutdownException, MultiThreadedExecutor, SingleThreadedExecutor

    from diffctl import ros_args as process_ros_args

    # diffctl's entry point took the process's `--ros-args` (the container's name and namespace) aside.
    rclpy.init(args=[sys.argv[0], *ros_args, "--ros-args", *process_ros_args.current_argv()])
    container = rclpy.create_node("ComponentManager")
    executor = MultiThreadedExecutor() if multi_threaded else SingleThreadedExecutor()
    executor.add_node(container)
    nodes = []
    for request in json.loads(nodes_json):
        try:
            cls = load_class(request["plugin"])
            node = cls(cli_args=request["cli_args"], use_global_arguments=False)  # the container's are its own
        except Exception as e:  # as the container's LoadNode answer: this node fails, the container stays
            container.get_logger().error(f"Failed to load node '{request['plugin']}': {type(e).__name__}: {e}")
            continue
        nodes.append(node)
        executor.add_node(node)
        print(f"Loaded node '{node.get_fully_qualified_name()}' in container "
              f"'{container.get_fully_qualified_name()}'", flush=True)
    try:
        executor.spin()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        for node in nodes:
            node.destroy_node()
        container.destroy_node()
        rclpy.try_shutdown()
