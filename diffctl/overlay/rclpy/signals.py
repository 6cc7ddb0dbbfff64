"""rclpy.signals (diffctl: diffctl.client.signals)."""

from diffctl.client.signals import *  # noqa: F403
