"""rclpy.guard_condition (diffctl: diffctl.client.guard_condition)."""

from diffctl.client.guard_condition import *  # noqa: F403
