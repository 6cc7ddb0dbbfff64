"""rclpy.time (diffctl: diffctl.client.ros_time)."""

from diffctl.client.ros_time import *  # noqa: F403
