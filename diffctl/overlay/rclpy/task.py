"""rclpy.task (diffctl: diffctl.client.task)."""

from diffctl.client.task import *  # noqa: F403
