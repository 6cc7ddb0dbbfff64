"""rclpy.logging (diffctl: diffctl.client.ros_logging)."""

from diffctl.client.ros_logging import *  # noqa: F403
