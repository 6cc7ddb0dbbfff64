"""rclpy.parameter_event_handler (diffctl: diffctl.client.parameter_event_handler)."""

from diffctl.client.parameter_event_handler import *  # noqa: F403
