"""`OnIncludeLaunchDescription`: how a LaunchService visits the descriptions included into it."""

from __future__ import annotations

from typing import Any

from ..event_handler import EventHandler
from ..events.include_launch_description import IncludeLaunchDescription
from ..utilities.class_tools_impl import is_a_subclass


def _carried(context: Any) -> list:
    return [context.locals.event.launch_description]


class OnIncludeLaunchDescription(EventHandler):
    """Gives the launch description an `IncludeLaunchDescription` event carries."""

    def __init__(self, **kwargs: Any) -> None:
        from ..actions.opaque_function import OpaqueFunction

        super().__init__(
            matcher=lambda event: is_a_subclass(event, IncludeLaunchDescription),
            entities=OpaqueFunction(function=_carried), **kwargs)
        self._event_kinds = (IncludeLaunchDescription,)

    @property
    def handler_description(self) -> str:
        return 'returns the launch_description in the event'

    @property
    def matcher_description(self) -> str:
        return 'event issubclass of launch.events.IncludeLaunchDescription'
