"""`BaseEventHandler` and `EventHandler`: what the launch does when an event happens."""

from __future__ import annotations

from collections.abc import Callable, Hashable
from typing import TYPE_CHECKING

from ._private.ros_names import default_text
from .event import Event
from .some_entities_type import SomeEntitiesType

if TYPE_CHECKING:
    from .launch_context import LaunchContext


class BaseEventHandler:
    """Takes the events `matcher(event)` accepts; `handle(event, context)` returns entities to visit.

    While they are visited, `context.locals.event` is the event (`LocalSubstitution('event.pid')`).
    A `handle_once` handler unregisters itself when it handles its first event.
    """

    def __repr__(self) -> str:
        return default_text(self)  # under ROS's module names, as ros2 launch --print shows it

    # The event classes outside which the matcher never accepts anything (None: it may accept any event).
    # launch's own handlers say it, so that a launch of many processes does not ask each process's handlers
    # about every other kind of event; see `_takes_only`.
    _event_kinds: tuple[type[Event], ...] | None = None
    # Set when the matcher only ever accepts events about one action (see launch._private.handler_index).
    _only_about: Hashable | None = None

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


def _takes_only(handler: BaseEventHandler, *kinds: type[Event]) -> BaseEventHandler:
    """`handler`, known to accept only events of `kinds` (its matcher starts with that isinstance test)."""
    handler._event_kinds = kinds
    return handler


def _may_take(handler: BaseEventHandler, kind: type[Event]) -> bool:
    """Whether `handler` may accept an event of class `kind`; only a handler whose `matches` is the
    matcher it was given (no subclass's own) is judged by its kinds."""
    kinds = getattr(handler, '_event_kinds', None)
    if kinds is None or type(handler).matches is not BaseEventHandler.matches:
        return True
    return issubclass(kind, kinds)


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
