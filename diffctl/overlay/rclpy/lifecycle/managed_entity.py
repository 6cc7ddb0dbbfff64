"""rclpy.lifecycle.managed_entity, from diffctl.client.lifecycle."""

from diffctl.client.lifecycle.managed_entity import ManagedEntity, SimpleManagedEntity  # noqa: F401
