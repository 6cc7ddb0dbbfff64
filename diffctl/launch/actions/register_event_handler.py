"""`RegisterEventHandler`: add an event handler to the launch."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from ..action import Action
from ..utilities.normalize_to_list_of_entities_impl import normalize_to_list_of_entities

if TYPE_CHECKING:
    from ..event_handler import BaseEventHandler
    from ..launch_context import LaunchContext
    from ..launch_description_entity import LaunchDescriptionEntity


class RegisterEventHandler(Action):
    """Registers `event_handler` when executed, ahead of those registered before.

    The event being handled at that moment, if any, is not offered to it.
    """

    def __init__(self, event_handler: BaseEventHandler, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self._handler = event_handler

    @property
    def event_handler(self) -> BaseEventHandler:
        return self._handler

    def execute(self, context: LaunchContext) -> None:
        context.register_event_handler(self._handler)

    def describe_conditional_sub_entities(self) -> list[tuple[str, Iterable[LaunchDescriptionEntity]]]:
        condition_text, entities = self._handler.describe()
        if not entities:
            return []
        return [(condition_text, normalize_to_list_of_entities(entities))]
