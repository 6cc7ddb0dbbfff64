"""rclpy.experimental: the EventsExecutor, which here is the single-threaded executor (same callback order)."""

from __future__ import annotations

from typing import Any

from diffctl.client.executors import SingleThreadedExecutor


def EventsExecutor(*, context: Any = None) -> SingleThreadedExecutor:
    return SingleThreadedExecutor(context=context)
