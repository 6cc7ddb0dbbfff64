"""rclpy.type_hash (diffctl: diffctl.client.type_hash)."""

from diffctl.client.type_hash import TypeHash  # noqa: F401
