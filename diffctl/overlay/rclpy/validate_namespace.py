"""rclpy.validate_namespace (diffctl: diffctl.client.names)."""

from diffctl.client.names import validate_namespace  # noqa: F401
