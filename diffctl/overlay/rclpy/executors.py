"""rclpy.executors (diffctl: diffctl.client.executors)."""

from diffctl.client.executors import *  # noqa: F403
