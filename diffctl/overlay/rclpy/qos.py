"""rclpy.qos (diffctl: diffctl.client.qos)."""

from diffctl.client.qos import *  # noqa: F403
