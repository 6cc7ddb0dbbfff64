"""`OnShutdown`: react when the launch begins to end."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from ..event import Event
from ..event_handler import BaseEventHandler
from ..events.shutdown import Shutdown
from ..some_entities_type import SomeEntitiesType
from ..utilities.class_tools_impl import is_a_subclass

if TYPE_CHECKING:
    from ..launch_context import LaunchContext


def gen_handler(entities: SomeEntitiesType) -> Callable[[Shutdown, LaunchContext], SomeEntitiesType]:
    """A callable `(event, context)` giving `entities` whatever it is called with."""

    def handler(event: Shutdown, context: LaunchContext) -> SomeEntitiesType:  # named so in --print, as in ROS
        return entities

    return handler


class OnShutdown(BaseEventHandler):
    """Gives `on_shutdown` (entities, or a callable `(event, context)`) for the Shutdown event.

    By the time it runs the launch counts as shut down: processes it would start do not start.
    """

    def __init__(
        self,
        *,
        on_shutdown: SomeEntitiesType | Callable[[Shutdown, LaunchContext], SomeEntitiesType | None],
        **kwargs: Any,
    ) -> None:
        super().__init__(matcher=lambda event: is_a_subclass(event, Shutdown), **kwargs)
        self._event_kinds = (Shutdown,)
        self._reaction = on_shutdown if callable(on_shutdown) else gen_handler(on_shutdown)

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        super().handle(event, context)
        return self._reaction(event, context)

    @property
    def handler_description(self) -> str:
        return str(self._reaction)

    @property
    def matcher_description(self) -> str:
        return 'event issubclass of launch.events.Shutdown'
