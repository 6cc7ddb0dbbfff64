"""rclpy.wait_for_message (diffctl: diffctl.client.wait_for_message)."""

from diffctl.client.wait_for_message import *  # noqa: F403
