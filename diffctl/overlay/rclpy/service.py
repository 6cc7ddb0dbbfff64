"""rclpy.service (diffctl: diffctl.client.service)."""

from diffctl.client.service import *  # noqa: F403
