"""rclpy.impl.rcutils_logger (diffctl: diffctl.client.ros_logging)."""

from diffctl.client.ros_logging import RcutilsLogger, get_logger  # noqa: F401
