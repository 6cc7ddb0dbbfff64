"""rclpy.duration (diffctl: diffctl.client.duration)."""

from typing import Protocol

from diffctl.client.duration import *  # noqa: F403


class DurationType(Protocol):
    """The type of a duration's handle (rclpy's binding of rcl_duration_t)."""

    nanoseconds: int
