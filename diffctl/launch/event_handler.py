"""`BaseEventHandler` and `EventHandler`: what the launch does when an event happens."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from .event import Event
from .some_entities_type import SomeEntitiesType

if TYPE_CHECKING:
    from .launch_context import LaunchContext


class BaseEventHandler:
    """Matches events with `matcher(event)` and handles them with `handle(event, context)`.

    While the entities a handler returns are visited, `context.locals.event` is the event being
    handled (e.g. `LocalSubstitution('event.name')`). With `handle_once` the handler unregisters
    itself the first time it handles an event.
    """

    def __init__(self, *, matcher: Callable[[Event], bool], handle_once: bool = False):
        self.__matcher = matcher
        self.__handle_once = handle_once

    @property
    def handle_once(self) -> bool:
        """Whether the handler unregisters after handling one event."""
        return self.__handle_once

    @property
    def handler_description(self) -> str | None:
        """Text describing what the handler does (subclasses say)."""
        return None

    @property
    def matcher_description(self) -> str | None:
        """Text describing which events the handler takes (subclasses say)."""
        return None

    def matches(self, event: Event) -> bool:
        """True when this handler takes `event`."""
        return self.__matcher(event)

    def describe(self) -> tuple[str, list[SomeEntitiesType]]:
        """(text, entities the handler would yield when known in advance)."""
        text = (f"{type(self).__name__}(matcher='{self.matcher_description}', "
                f"handler='{self.handler_description}', handle_once={self.handle_once})")
        return text, []

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        """Set `event` in the context's locals and unregister a handle-once handler.

        Subclasses call this first, then return the entities to visit.
        """
        context.extend_locals({'event': event})
        if self.handle_once:
            context.unregister_event_handler(self)
        return None


class EventHandler(BaseEventHandler):
    """An event handler yielding fixed `entities` for every event its matcher takes."""

    def __init__(
        self,
        *,
        matcher: Callable[[Event], bool],
        entities: SomeEntitiesType | None = None,
        handle_once: bool = False,
    ) -> None:
        super().__init__(matcher=matcher, handle_once=handle_once)
        self.__entities = entities

    @property
    def entities(self) -> SomeEntitiesType | None:
        """What the handler yields."""
        return self.__entities

    def describe(self) -> tuple[str, list[SomeEntitiesType]]:
        text, entities = super().describe()
        if self.entities:
            entities.extend(self.entities)
        return text, entities

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        super().handle(event, context)
        return self.entities
