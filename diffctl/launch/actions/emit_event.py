"""`EmitEvent`: put an event on the launch's queue."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..action import Action
from ..event import Event
from ..utilities.class_tools_impl import is_a_subclass

if TYPE_CHECKING:
    from ..launch_context import LaunchContext


class EmitEvent(Action):
    """Queues `event` when executed; it is handled after the event being handled now."""

    def __init__(self, *, event: Event, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        if not is_a_subclass(event, Event):
            raise RuntimeError(f"EmitEvent() expected an event instance, got '{event}'.")
        self._queued = event

    @property
    def event(self) -> Event:
        return self._queued

    def execute(self, context: LaunchContext) -> None:
        context.emit_event_sync(self._queued)
