"""rclpy.context (diffctl: diffctl.client.context)."""

from typing import Protocol

from diffctl.client.context import *  # noqa: F403


class ContextHandle(Protocol):
    """The type of a context's handle (rclpy's binding of rcl_context_t)."""
