"""rclpy.publisher (diffctl: diffctl.client.publisher)."""

from diffctl.client.publisher import *  # noqa: F403
