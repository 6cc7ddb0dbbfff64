"""rclpy.parameter_client (diffctl: diffctl.client.parameter_client)."""

from diffctl.client.parameter_client import *  # noqa: F403
