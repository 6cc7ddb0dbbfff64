"""rclpy.validate_full_topic_name (diffctl: diffctl.client.names)."""

from diffctl.client.names import validate_full_topic_name  # noqa: F401
