"""rclpy.clock_type (diffctl: diffctl.client.clock_type)."""

from diffctl.client.clock_type import *  # noqa: F403
