"""rclpy.publisher (diffctl: diffctl.client.publisher)."""

from typing import TypeVar

from diffctl.client.publisher import *  # noqa: F403

MsgType = TypeVar("MsgType")
