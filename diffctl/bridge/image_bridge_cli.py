"""`diffctl image-bridge`: ros_gz_image's image_bridge — gz image topics to sensor_msgs/msg/Image, same names.

As ros_gz_image (jazzy, src/image_bridge.cpp): node `ros_gz_image`, one gz→ROS entry per topic argument, the
gz side always subscribed, parameter `qos` = `default` | `system_default` | `sensor_data` (anything else is
logged as an error and `default` used). image_transport's raw transport only: no `/compressed` topics, and
no camera_info (ros_gz_image bridges none either).
"""

from __future__ import annotations

import dataclasses
from typing import Any

import click

from diffctl import ros_args
from diffctl.bridge.config import QOS_PROFILES, BridgeEntry, parse_cli_entry
from diffctl.errors import ConfigError

NODE_NAME = "ros_gz_image"
QOS_BY_PARAM = {
    "default": QOS_PROFILES["DEFAULT"],
    "system_default": QOS_PROFILES["SYSTEM_DEFAULT"],
    "sensor_data": QOS_PROFILES["SENSOR_DATA"],
}


def image_entries(topics: tuple[str, ...], qos: str = "default") -> tuple[list[BridgeEntry], str | None]:
    """The entries for `topics`, and an error line when `qos` is not one of image_bridge's."""
    if not topics:
        raise ConfigError(
            "no image topic given",
            hint="image_bridge <topic> <topic> ..  e.g. diffctl image-bridge /camera/front/image_raw",
        )
    problem = None
    profile = QOS_BY_PARAM.get(str(qos))
    if profile is None:
        problem = f"Invalid QoS profile {qos} specified. Using default profile."
        profile = QOS_BY_PARAM["default"]
    entries = []
    for i, topic in enumerate(topics):
        entry = parse_cli_entry(f"{topic}@sensor_msgs/msg/Image[gz.msgs.Image", i)
        entries.append(dataclasses.replace(entry, qos=profile))
    return entries, problem


@click.command("image-bridge", context_settings={"help_option_names": ["-h", "--help"]})
@click.argument("topics", nargs=-1)
def image_bridge(topics: tuple[str, ...]) -> int:
    """Bridge gz image topics to sensor_msgs/msg/Image on the same names, as ros_gz_image's image_bridge.

    \b
    Example:
      diffctl image-bridge /camera/image /depth_camera
      diffctl image-bridge /camera/image --ros-args -p qos:=sensor_data
    """
    ra = ros_args.current(NODE_NAME)
    entries, problem = image_entries(topics, ra.params.get("qos", "default"))

    from diffctl.bridge.cli import make_node
    from diffctl.client import component

    def make() -> Any:
        # ros_gz_image declares `qos` (string, "default") and starts its subscriptions at once
        node = make_node(entries, NODE_NAME, (("qos", "default"),))
        if problem:
            node.get_logger().error(problem)
        return node

    return component.run(make)
