"""rclpy.client (diffctl: diffctl.client.client)."""

from diffctl.client.client import *  # noqa: F403
