"""`OnShutdown`: handle the launch's shutdown."""

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
    """A handler callable that always returns `entities`."""
    def handler(event: Shutdown, context: LaunchContext) -> SomeEntitiesType:
        return entities

    return handler


class OnShutdown(BaseEventHandler):
    """Yields `on_shutdown` (entities, or a callable `(event, context)`) when the launch shuts down."""

    def __init__(
        self,
        *,
        on_shutdown: SomeEntitiesType | Callable[[Shutdown, LaunchContext], SomeEntitiesType | None],
        **kwargs: Any,
    ) -> None:
        super().__init__(matcher=lambda event: is_a_subclass(event, Shutdown), **kwargs)
        self.__on_shutdown = on_shutdown if callable(on_shutdown) else gen_handler(on_shutdown)

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        super().handle(event, context)
        return self.__on_shutdown(event, context)

    @property
    def handler_description(self) -> str:
        return f'{self.__on_shutdown}'

    @property
    def matcher_description(self) -> str:
        return 'event issubclass of launch.events.Shutdown'
