"""rclpy.service_introspection (diffctl: diffctl.client.service_introspection)."""

from diffctl.client.service_introspection import ServiceIntrospectionState  # noqa: F401
