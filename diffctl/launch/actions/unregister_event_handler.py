"""`UnregisterEventHandler`: take an event handler off the launch."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..action import Action

if TYPE_CHECKING:
    from ..event_handler import BaseEventHandler
    from ..launch_context import LaunchContext


class UnregisterEventHandler(Action):
    """Unregisters `event_handler` when executed; one that is not registered is a ValueError."""

    def __init__(self, event_handler: BaseEventHandler, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self._handler = event_handler

    @property
    def event_handler(self) -> BaseEventHandler:
        return self._handler

    def execute(self, context: LaunchContext) -> None:
        context.unregister_event_handler(self._handler)
