"""rclpy.validate_topic_name (diffctl: diffctl.client.names)."""

from diffctl.client.names import validate_topic_name  # noqa: F401

TOPIC_SEPARATOR_STRING = "/"
