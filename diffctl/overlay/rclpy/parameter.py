"""rclpy.parameter (diffctl: diffctl.client.parameter)."""

from diffctl.client.parameter import *  # noqa: F403
