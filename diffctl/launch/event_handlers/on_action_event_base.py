"""`OnActionEventBase`: handlers of one kind of event about actions (a process started, exited, …)."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any

from .._private.handler_index import about_action
from ..event import Event
from ..event_handler import BaseEventHandler
from ..events.process.process_targeted_event import ProcessTargetedEvent
from ..events.process.running_process_event import RunningProcessEvent
from ..launch_description_entity import LaunchDescriptionEntity
from ..some_entities_type import SomeEntitiesType

if TYPE_CHECKING:
    from ..action import Action
    from ..launch_context import LaunchContext


def _action_test(chosen: Any) -> Callable[[Any], bool]:
    """What `action_matcher` says about an event's action: anything (None), itself (an action), or a call."""
    if chosen is None:
        return lambda action: True
    if callable(chosen):
        return chosen
    return lambda action: action is chosen


def _fixed_entities(on_event: Any) -> list[LaunchDescriptionEntity]:
    if not isinstance(on_event, Iterable):
        return [on_event]
    listed = list(on_event)
    for item in listed:
        if not isinstance(item, LaunchDescriptionEntity):
            raise TypeError(
                "expected all items in 'on_event' iterable to be of type "
                f"'LaunchDescriptionEntity' but got '{type(item)}'")
    return listed


class OnActionEventBase(BaseEventHandler):
    """Takes the events of `target_event_cls` about the actions `action_matcher` chooses.

    `action_matcher`: None for any action, one `target_action_cls` instance for that very action, or a
    predicate on the action. `on_event`: the entities to give, or a callable `(event, context)` that
    returns them.
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
        if action_matcher is not None and not callable(action_matcher) \
                and not isinstance(action_matcher, target_action_cls):
            raise TypeError(f"action_matcher must be an '{target_action_cls.__name__}' instance or a callable")
        chooses = _action_test(action_matcher)
        super().__init__(
            matcher=lambda event: isinstance(event, target_event_cls) and chooses(event.action), **kwargs)
        self._kinds = (target_event_cls, target_action_cls, action_matcher is not None)
        self._event_kinds = (target_event_cls,)
        if action_matcher is not None and not callable(action_matcher) \
                and issubclass(target_event_cls, RunningProcessEvent) \
                and not issubclass(target_event_cls, ProcessTargetedEvent):
            # it takes the events of that one action only: a launch need not ask it about other processes'
            self._only_about = about_action(action_matcher)
        self._reaction = on_event if callable(on_event) else None
        self._given = [] if callable(on_event) else _fixed_entities(on_event)

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        super().handle(event, context)
        return self._given if self._given else self._reaction(event, context)

    def describe(self) -> tuple[str, list[SomeEntitiesType]]:
        line, known = super().describe()
        return line, known + self._given

    @property
    def handler_description(self) -> str:
        return '<actions>' if self._given else str(self._reaction)

    @property
    def matcher_description(self) -> str:
        event_type, action_type, narrowed = self._kinds
        text = f'event == {event_type.__name__}'
        return f'{text} and {action_type.__name__}(event.action)' if narrowed else text
