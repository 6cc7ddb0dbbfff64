"""rclpy.timer (diffctl: diffctl.client.timer)."""

from diffctl.client.timer import *  # noqa: F403
