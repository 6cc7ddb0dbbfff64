"""rclpy.qos_event, the older name of rclpy.event_handler (diffctl: diffctl.client.event_handler)."""

from diffctl.client.event_handler import *  # noqa: F403
