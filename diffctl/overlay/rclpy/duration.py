"""rclpy.duration (diffctl: diffctl.client.duration)."""

from diffctl.client.duration import *  # noqa: F403
