"""rclpy.subscription (diffctl: diffctl.client.subscription)."""

from diffctl.client.subscription import *  # noqa: F403
