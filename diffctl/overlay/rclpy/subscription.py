"""rclpy.subscription (diffctl: diffctl.client.subscription)."""

from typing import TypeVar

from diffctl.client.subscription import *  # noqa: F403

MsgType = TypeVar("MsgType")
