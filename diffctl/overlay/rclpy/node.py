"""rclpy.node (diffctl: diffctl.client.node)."""

from diffctl.client.node import *  # noqa: F403
