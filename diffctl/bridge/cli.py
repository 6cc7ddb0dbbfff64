"""`diffctl bridge`: ros_gz_bridge's parameter_bridge — a YAML config and/or `/TOPIC@ROS_TYPE@GZ_TYPE` args."""

from __future__ import annotations

import dataclasses
from typing import Any

import click

from diffctl import ros_args
from diffctl.bridge.config import BridgeEntry, GzNamespace, load_config, parse_cli_entry
from diffctl.errors import ConfigError, ParameterError

NODE_NAME = "ros_gz_bridge"


def _bool_param(params: dict[str, Any], name: str) -> bool:
    value = params.get(name, False)
    if isinstance(value, bool):
        return value
    raise ParameterError(f"{value!r} invalid; valid: true, false", field=name)


def collect_entries(
    topics: tuple[str, ...],
    config_file: str | None,
    params: dict[str, Any],
    namespace: str | None,
    node_name: str = NODE_NAME,
) -> list[BridgeEntry]:
    """Every entry from the config file and the command line, validated before anything starts."""
    config_file = config_file or params.get("config_file") or None
    # As parameter_bridge: only the config file's gz names are expanded, never the command-line ones.
    gz_namespace = GzNamespace(namespace or "/", node_name) if _bool_param(params, "expand_gz_topic_names") else None
    entries: list[BridgeEntry] = []
    if config_file:
        entries += load_config(str(config_file), gz_namespace=gz_namespace)
    # parameter_bridge's `lazy` parameter makes every command-line entry lazy
    lazy = _bool_param(params, "lazy")
    entries += [dataclasses.replace(parse_cli_entry(arg, i), lazy=lazy) if lazy else parse_cli_entry(arg, i)
                for i, arg in enumerate(topics)]
    if not entries:
        raise ConfigError(
            "nothing to bridge",
            hint="give --config FILE, --ros-args -p config_file:=FILE or /TOPIC@ROS_TYPE@GZ_TYPE arguments",
        )
    return entries


@click.command("bridge", context_settings={"help_option_names": ["-h", "--help"]})
@click.argument("topics", nargs=-1)
@click.option(
    "--config",
    "-c",
    "config_file",
    type=click.Path(dir_okay=False),
    help="ros_gz_bridge YAML config (also: --ros-args -p config_file:=FILE).",
)
def bridge(topics: tuple[str, ...], config_file: str | None) -> int:
    """Bridge simulator-side (gz) topics and ROS topics, as ros_gz_bridge's parameter_bridge does.

    TOPICS are `/TOPIC@ROS_TYPE@GZ_TYPE`: `@` both ways, `[` gz to ROS, `]` ROS to gz. The YAML config
    takes ros_gz_bridge's keys as is: topic_name, ros_topic_name, gz_topic_name, ros_type_name,
    gz_type_name, direction, lazy, publisher_queue, subscriber_queue, qos_profile.

    \b
    Example:
      diffctl bridge --config config/bridge_config.yaml
      diffctl bridge /clock@rosgraph_msgs/msg/Clock[gz.msgs.Clock
      diffctl bridge --ros-args -p config_file:=config/bridge_config_control.yaml
    """
    ra = ros_args.current(NODE_NAME)
    entries = collect_entries(topics, config_file, ra.params, ra.namespace, ra.node_name or NODE_NAME)
    from diffctl.client import component

    return component.run(lambda: make_node(entries))


# ros_gz_bridge's RosGzBridge node and parameter_bridge's main declare these, without descriptors
DECLARED = (("subscription_heartbeat", 1000), ("config_file", ""), ("expand_gz_topic_names", False),
            ("override_timestamps_with_wall_time", False), ("lazy", False))


def make_node(entries: list[BridgeEntry], node_name: str = NODE_NAME, declared: Any = DECLARED) -> Any:
    """The bridge's client Node with its parameters, its channels started (closed when the node shuts down)."""
    from diffctl.bridge.bridge import Bridge
    from diffctl.client.node import Node

    node = Node(node_name, client_library="rclcpp")
    for name, default in declared:
        node.declare_parameter(name, default)
    running = Bridge(node, entries)
    node.context.on_shutdown(lambda: running.close())
    running.start()
    log = node.get_logger()
    for e in entries:
        if e.direction.to_ros:
            log.info(f"Creating GZ->ROS Bridge: [{e.gz_topic} ({e.gz_type}) -> {e.ros_topic} ({e.ros_type})]"
                     f" (Lazy {int(e.lazy)})")
        if e.direction.to_gz:
            log.info(f"Creating ROS->GZ Bridge: [{e.ros_topic} ({e.ros_type}) -> {e.gz_topic} ({e.gz_type})]"
                     f" (Lazy {int(e.lazy)})")
    return node
