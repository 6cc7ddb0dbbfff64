"""rclpy.lifecycle.managed_entity, from diffctl.client.lifecycle."""

from diffctl.client.lifecycle.managed_entity import (  # noqa: F401
    ManagedEntity,
    SimpleManagedEntity,
    TransitionCallbackReturn,
)
