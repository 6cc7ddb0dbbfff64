"""`BaseEventHandler` and `EventHandler`: what the launch does when an event happens."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from .event import Event
from .some_entities_type import SomeEntitiesType

if TYPE_CHECKING:
    from .launch_context import LaunchContext


class BaseEventHandler:
    """Takes the events `matcher(event)` accepts; `handle(event, context)` returns entities to visit.

    While they are visited, `context.locals.event` is the event (`LocalSubstitution('event.pid')`).
    A `handle_once` handler unregisters itself when it handles its first event.
    """

    def __init__(self, *, matcher: Callable[[Event], bool], handle_once: bool = False):
        self._accepts = matcher
        self._once = handle_once

    @property
    def handle_once(self) -> bool:
        return self._once

    @property
    def handler_description(self) -> str | None:
        """What handling does, in words (None here; subclasses say)."""
        return None

    @property
    def matcher_description(self) -> str | None:
        """Which events are taken, in words (None here; subclasses say)."""
        return None

    def matches(self, event: Event) -> bool:
        return self._accepts(event)

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        """Make `event` a local and, for a handle-once handler, unregister it.

        Subclasses call it before computing what to return.
        """
        if self._once:
            context.unregister_event_handler(self)
        context.extend_locals({'event': event})
        return None

    def describe(self) -> tuple[str, list[SomeEntitiesType]]:
        """A line about the handler, and the entities it would give when they are known beforehand."""
        kind, takes, does = type(self).__name__, self.matcher_description, self.handler_description
        return f"{kind}(matcher='{takes}', handler='{does}', handle_once={self._once})", []


class EventHandler(BaseEventHandler):
    """Gives the same `entities` for every event `matcher` accepts."""

    def __init__(
        self,
        *,
        matcher: Callable[[Event], bool],
        entities: SomeEntitiesType | None = None,
        handle_once: bool = False,
    ) -> None:
        super().__init__(matcher=matcher, handle_once=handle_once)
        self._gives = entities

    @property
    def entities(self) -> SomeEntitiesType | None:
        return self._gives

    def describe(self) -> tuple[str, list[SomeEntitiesType]]:
        line, known = super().describe()
        if self._gives:
            known += list(self._gives)
        return line, known

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        super().handle(event, context)
        return self._gives
