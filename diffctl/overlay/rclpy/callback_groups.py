"""rclpy.callback_groups (diffctl: diffctl.client.callback_groups)."""

from diffctl.client.callback_groups import *  # noqa: F403
