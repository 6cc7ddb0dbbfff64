"""rclpy.type_support (diffctl: diffctl.client.type_support)."""

from diffctl.client.type_support import *  # noqa: F403
