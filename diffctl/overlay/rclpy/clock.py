"""rclpy.clock (diffctl: diffctl.client.clock)."""

from diffctl.client.clock import *  # noqa: F403
