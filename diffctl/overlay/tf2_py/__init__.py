"""tf2_py (ROS's Python binding of tf2): exceptions and BufferCore, from diffctl.tf2."""

# ROS's tf2_py extension imports rclpy.time when it loads (it builds rclpy Time objects), so code written
# against it may reach `rclpy.time` after a bare `import rclpy`.
import rclpy.time  # noqa: F401

from diffctl.tf2.exceptions import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TimeoutException,
    TransformException,
)
from diffctl.tf2.ros_io import BufferCore

__all__ = [
    "BufferCore",
    "ConnectivityException",
    "ExtrapolationException",
    "InvalidArgumentException",
    "LookupException",
    "TimeoutException",
    "TransformException",
]
