"""rclpy.wait_for_message: one message from a topic, or (False, None) after the timeout."""

from __future__ import annotations

import time
from typing import Any

from diffctl.client import waiting


def wait_for_message(msg_type: Any, node: Any, topic: str, *, qos_profile: Any = 1,
                     time_to_wait: float = -1) -> tuple[bool, Any]:
    context = node.context
    got: list[Any] = []

    def keep(msg: Any) -> None:
        got.append(msg)

    sub = node.create_subscription(msg_type, topic, keep, qos_profile)
    deadline = None if time_to_wait is None or time_to_wait < 0 else time.monotonic() + time_to_wait
    try:
        while context.ok():
            generation = waiting.SIGNAL.generation
            work = sub._take()
            if work is not None:
                coro = work()
                try:
                    coro.send(None)
                except StopIteration:
                    pass
                if got:
                    return True, got[0]
            left = None if deadline is None else deadline - time.monotonic()
            if left is not None and left <= 0:
                return False, None
            waiting.SIGNAL.wait(generation, 0.1 if left is None else min(left, 0.1))
        return False, None
    finally:
        node.destroy_subscription(sub)
