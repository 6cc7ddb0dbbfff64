"""rclpy.lifecycle.node, from diffctl.client.lifecycle."""

from diffctl.client.lifecycle.managed_entity import TransitionCallbackReturn  # noqa: F401
from diffctl.client.lifecycle.node import LifecycleNode, LifecycleNodeMixin, LifecycleState  # noqa: F401
