"""rclpy.serialization (diffctl: diffctl.client.serialization)."""

from diffctl.client.serialization import *  # noqa: F403
