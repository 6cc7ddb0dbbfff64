"""rclpy.time (diffctl: diffctl.client.ros_time)."""

from typing import Protocol

from diffctl.client.ros_time import *  # noqa: F403


class TimeHandle(Protocol):
    """The type of a time's handle (rclpy's binding of rcl_time_point_t)."""

    nanoseconds: int
