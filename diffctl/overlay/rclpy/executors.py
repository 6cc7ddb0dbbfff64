"""rclpy.executors (diffctl: diffctl.client.executors)."""

from typing import TypeVar

from diffctl.client.exceptions import InvalidHandle  # noqa: F401
from diffctl.client.executors import *  # noqa: F403
from diffctl.client.timer import await_or_execute  # noqa: F401

WaitableEntityType = TypeVar("WaitableEntityType")
