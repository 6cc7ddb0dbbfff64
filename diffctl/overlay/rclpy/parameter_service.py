"""rclpy.parameter_service (diffctl: diffctl.client.parameter_service)."""

from diffctl.client.parameter_service import ParameterService  # noqa: F401

TOPIC_SEPARATOR_STRING = "/"
