"""rclpy.guard_condition.GuardCondition: a thread-safe trigger that makes an executor run its callback."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from diffctl.client import waiting
from diffctl.client.destroyable import Handle, handle_of
from diffctl.client.timer import await_or_execute


class GuardCondition:
    def __init__(self, callback: Callable[[], Any] | None, callback_group: Any, context: Any = None) -> None:
        self.callback = callback
        self.callback_group = callback_group
        self._executor_event = False
        self._executor_triggered = False
        self._destroyed = False
        self._node: Any = None

    @property
    def handle(self) -> Handle:
        return handle_of(self)

    def __enter__(self) -> GuardCondition:
        return self

    def __exit__(self, *exc: Any) -> None:
        pass

    def trigger(self) -> None:
        self._executor_triggered = True
        waiting.notify()

    def _ready(self) -> bool:
        return self._executor_triggered and not self._destroyed

    def _take(self) -> Callable[[], Any] | None:
        self._executor_triggered = False
        callback = self.callback

        async def _execute() -> None:
            if callback is not None:
                await await_or_execute(callback)

        return _execute

    def destroy(self) -> None:
        if self._node is not None:
            self._node.destroy_guard_condition(self)
        else:
            self._destroyed = True
