"""rclpy.logging_service (diffctl: diffctl.client.logging_service)."""

from diffctl.client.logging_service import LoggingService  # noqa: F401

TOPIC_SEPARATOR_STRING = "/"
