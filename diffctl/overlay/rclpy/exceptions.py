"""rclpy.exceptions (diffctl: diffctl.client.exceptions)."""

from diffctl.client.exceptions import *  # noqa: F403
