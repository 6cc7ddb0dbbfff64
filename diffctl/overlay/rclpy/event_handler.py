"""rclpy.event_handler (diffctl: diffctl.client.event_handler)."""

from diffctl.client.event_handler import *  # noqa: F403
