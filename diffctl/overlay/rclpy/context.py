"""rclpy.context (diffctl: diffctl.client.context)."""

from diffctl.client.context import *  # noqa: F403
