"""rclpy.expand_topic_name (diffctl: diffctl.client.names)."""

from diffctl.client.names import expand_topic_name  # noqa: F401
