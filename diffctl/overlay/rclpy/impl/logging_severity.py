"""rclpy.impl.logging_severity (diffctl: diffctl.client.ros_logging)."""

from diffctl.client.ros_logging import LoggingSeverity  # noqa: F401
