"""rclpy.lifecycle.publisher, from diffctl.client.lifecycle."""

from diffctl.client.lifecycle.managed_entity import LifecyclePublisher  # noqa: F401
