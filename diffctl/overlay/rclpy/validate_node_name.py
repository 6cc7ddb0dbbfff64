"""rclpy.validate_node_name (diffctl: diffctl.client.names)."""

from diffctl.client.names import validate_node_name  # noqa: F401
