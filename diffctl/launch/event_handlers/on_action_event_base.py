"""`OnActionEventBase`: handlers of an event kind emitted about an action (a process start, an exit, …)."""

from __future__ import annotations

import collections.abc
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from ..event import Event
from ..event_handler import BaseEventHandler
from ..launch_description_entity import LaunchDescriptionEntity
from ..some_entities_type import SomeEntitiesType

if TYPE_CHECKING:
    from ..action import Action
    from ..launch_context import LaunchContext


class OnActionEventBase(BaseEventHandler):
    """Handles events of `target_event_cls` whose `event.action` the `action_matcher` selects.

    `action_matcher` is an action of `target_action_cls` (that very action), a callable taking the action,
    or None (any action). `on_event` is entities to yield, or a callable `(event, context)` returning them.
    """

    def __init__(
        self,
        *,
        action_matcher: Callable[[Action], bool] | Action | None,
        on_event: SomeEntitiesType | Callable[[Event, LaunchContext], SomeEntitiesType | None],
        target_event_cls: type[Event],
        target_action_cls: type[Action],
        **kwargs: Any,
    ) -> None:
        if not issubclass(target_event_cls, Event):
            raise TypeError("'target_event_cls' must be a subclass of 'Event'")
        if not isinstance(action_matcher, (target_action_cls, type(None))) and not callable(action_matcher):
            raise TypeError(f"action_matcher must be an '{target_action_cls.__name__}' instance or a callable")
        self.__target_action_cls = target_action_cls
        self.__target_event_cls = target_event_cls
        self.__action_matcher = action_matcher

        def matcher(event: Event) -> bool:
            if not isinstance(event, target_event_cls):
                return False
            if callable(action_matcher):
                return action_matcher(event.action)
            if isinstance(action_matcher, target_action_cls):
                return event.action is action_matcher
            return True

        super().__init__(matcher=matcher, **kwargs)
        self.__actions_on_event: list[LaunchDescriptionEntity] = []
        self.__on_event: Callable[[Event, LaunchContext], SomeEntitiesType | None] | None = None
        if callable(on_event):
            self.__on_event = on_event
        elif isinstance(on_event, collections.abc.Iterable):
            entities = list(on_event)
            for entity in entities:
                if not isinstance(entity, LaunchDescriptionEntity):
                    raise TypeError(
                        "expected all items in 'on_event' iterable to be of type "
                        f"'LaunchDescriptionEntity' but got '{type(entity)}'")
            self.__actions_on_event = entities
        else:
            self.__actions_on_event = [on_event]

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        super().handle(event, context)
        if self.__actions_on_event:
            return self.__actions_on_event
        return self.__on_event(event, context)

    def describe(self) -> tuple[str, list[SomeEntitiesType]]:
        text, entities = super().describe()
        entities.extend(self.__actions_on_event)
        return text, entities

    @property
    def handler_description(self) -> str:
        return '<actions>' if self.__actions_on_event else f'{self.__on_event}'

    @property
    def matcher_description(self) -> str:
        kind = self.__target_event_cls.__name__
        if self.__action_matcher is None:
            return f'event == {kind}'
        return f'event == {kind} and {self.__target_action_cls.__name__}(event.action)'
