"""rclpy.clock (diffctl: diffctl.client.clock)."""

from typing import Protocol, TypedDict

from diffctl.client.clock import *  # noqa: F403
from diffctl.client.clock_type import ClockType  # noqa: F401


class TimeJumpDictionary(TypedDict):
    """What a jump callback's post_callback gets from rcl: the clock change and the jump in nanoseconds."""

    clock_change: object
    delta: int


class ClockHandle(Protocol):
    """The type of a clock's handle (rclpy's binding of rcl_clock_t)."""
