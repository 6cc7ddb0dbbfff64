"""rclpy.waitable (diffctl: diffctl.client.waitable)."""

from diffctl.client.waitable import *  # noqa: F403
