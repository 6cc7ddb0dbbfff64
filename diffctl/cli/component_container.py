"""`diffctl component-container`: Python composable nodes in one process (rclcpp_components' component_container).

As rclcpp's ComponentManager, the container node (`ComponentManager` unless renamed) serves
`~/_container/load_node`, `~/_container/unload_node` and `~/_container/list_nodes`
(composition_interfaces), which launch_ros's LoadComposableNodes calls. A plugin is a Python class:
`module:Class`, or the name an `rclpy_components` entry point gives (`my_pkg::Talker`); it takes the node
options as keyword arguments (`cli_args`, `parameter_overrides`, …) and passes them to rclpy's Node. C++
components cannot be loaded: that request fails with a message naming the plugin, and the container stays.
`--nodes JSON` (plugins and their `--ros-args`, as the earlier engine gave them) loads nodes at start.
"""

from __future__ import annotations

import importlib
import json
import sys
import threading
from typing import Any

import click

from diffctl.errors import LaunchError

ENTRY_POINT_GROUP = "rclpy_components"


def load_class(plugin: str) -> Any:
    """The class of a Python component (LaunchError when the plugin names no Python class)."""
    from importlib.metadata import entry_points

    for ep in entry_points(group=ENTRY_POINT_GROUP):
        if ep.name == plugin:
            return ep.load()
    module, _, attr = plugin.partition(":")
    if not attr or "::" in plugin:
        raise LaunchError(
            f"component {plugin!r} is not a Python component (C++ components cannot be loaded)",
            hint=f"name a Python class as 'module:Class', or register it as an {ENTRY_POINT_GROUP!r} entry point",
        )
    return getattr(importlib.import_module(module), attr)


class ComponentManager:
    """The loaded nodes of a container and the services that load, unload and list them."""

    def __init__(self, container: Any, executor: Any) -> None:
        from composition_interfaces.srv import ListNodes, LoadNode, UnloadNode

        self.container, self.executor = container, executor
        self.nodes: dict[int, Any] = {}
        self.next_id = 1
        self.lock = threading.Lock()
        container.create_service(LoadNode, "~/_container/load_node", self.on_load_node)
        container.create_service(UnloadNode, "~/_container/unload_node", self.on_unload_node)
        container.create_service(ListNodes, "~/_container/list_nodes", self.on_list_nodes)

    def add(self, node: Any) -> int:
        with self.lock:
            unique_id, self.next_id = self.next_id, self.next_id + 1
            self.nodes[unique_id] = node
        self.executor.add_node(node)
        return unique_id

    def on_load_node(self, request: Any, response: Any) -> Any:
        from diffctl.client.parameter import Parameter

        try:
            cls = load_class(request.plugin_name)
        except Exception as e:
            self.container.get_logger().error(
                f"Failed to find class with the requested plugin name '{request.plugin_name}': {e}"
            )
            response.success, response.error_message = False, "Failed to find class with the requested plugin name."
            return response
        args = ["--ros-args"]
        if request.node_name:
            args += ["-r", f"__node:={request.node_name}"]
        if request.node_namespace:
            args += ["-r", f"__ns:={request.node_namespace}"]
        for rule in request.remap_rules:
            args += ["-r", rule]
        options: dict[str, Any] = {
            "cli_args": args,
            "use_global_arguments": False,  # the container's own name and namespace are not the node's
            "parameter_overrides": [Parameter.from_parameter_msg(p) for p in request.parameters],
        }
        for extra in request.extra_arguments:
            value = Parameter.from_parameter_msg(extra).value
            if extra.name == "use_intra_process_comms" and not isinstance(value, bool):
                response.success = False
                response.error_message = "Extra component argument 'use_intra_process_comms' must be a boolean"
                self.container.get_logger().error(response.error_message)
                return response
        try:
            node = cls(**options)
        except Exception as e:
            response.success = False
            response.error_message = f"Component constructor threw an exception: {type(e).__name__}: {e}"
            self.container.get_logger().error(response.error_message)
            return response
        response.unique_id = self.add(node)
        response.full_node_name = node.get_fully_qualified_name()
        response.success = True
        return response

    def on_unload_node(self, request: Any, response: Any) -> Any:
        with self.lock:
            node = self.nodes.pop(request.unique_id, None)
        if node is None:
            response.success = False
            response.error_message = f"No node found with unique_id: {request.unique_id}"
            self.container.get_logger().warning(response.error_message)
            return response
        self.executor.remove_node(node)
        node.destroy_node()
        response.success = True
        return response

    def on_list_nodes(self, request: Any, response: Any) -> Any:
        with self.lock:
            loaded = sorted(self.nodes.items())
        response.unique_ids = [i for i, _ in loaded]
        response.full_node_names = [n.get_fully_qualified_name() for _, n in loaded]
        return response


@click.command("component-container", context_settings={"ignore_unknown_options": True})
@click.option("--nodes", "nodes_json", default="[]", help="Composable nodes to load at start, as JSON.")
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
    manager = ComponentManager(container, executor)
    for request in json.loads(nodes_json):
        try:
            cls = load_class(request["plugin"])
            node = cls(cli_args=request["cli_args"], use_global_arguments=False)  # the container's are its own
        except Exception as e:  # as the container's LoadNode answer: this node fails, the container stays
            container.get_logger().error(f"Failed to load node '{request['plugin']}': {type(e).__name__}: {e}")
            continue
        manager.add(node)
        print(
            f"Loaded node '{node.get_fully_qualified_name()}' in container '{container.get_fully_qualified_name()}'",
            flush=True,
        )
    try:
        executor.spin()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        for node in list(manager.nodes.values()):
            node.destroy_node()
        container.destroy_node()
        rclpy.try_shutdown()
