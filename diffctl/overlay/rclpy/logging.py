"""rclpy.logging (diffctl: diffctl.client.ros_logging)."""

from diffctl.client.ros_logging import *  # noqa: F403
from diffctl.client.ros_logging import _root_logger  # noqa: F401  (user code logs through it before init)
