"""`TimerAction` (`<timer period=…>`): actions deferred by some time, unless canceled."""

from __future__ import annotations

import asyncio
import collections.abc
import warnings
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from .. import logging as launch_logging
from ..action import Action
from ..event_handler import EventHandler
from ..events.shutdown import Shutdown
from ..events.timer_event import TimerEvent
from ..frontend.expose import expose_action
from ..some_substitutions_type import SomeSubstitutionsType_types_tuple
from ..utilities import type_utils
from ..utilities.class_tools_impl import is_a_subclass
from ..utilities.ensure_argument_type_impl import ensure_argument_type
from .opaque_function import OpaqueFunction

if TYPE_CHECKING:
    from ..frontend.entity import Entity
    from ..frontend.parser import Parser
    from ..launch_context import LaunchContext
    from ..launch_description_entity import LaunchDescriptionEntity
    from ..some_entities_type import SomeEntitiesType
    from ..some_substitutions_type import SomeSubstitutionsType

# marks a context in which the handler dispatching TimerEvents is registered
_INSTALLED = '_TimerAction__event_handler_has_been_installed'


@expose_action('timer')
class TimerAction(Action):
    """Yields `actions` once `period` seconds have passed, unless canceled first (one shot).

    The context's locals of when the timer started are restored for the yielded actions. By default a
    shutdown cancels the timer (`cancel_on_shutdown`), so that pending timers do not hold the launch up.
    """

    def __init__(
        self,
        *,
        period: float | SomeSubstitutionsType,
        actions: Iterable[LaunchDescriptionEntity],
        cancel_on_shutdown: bool | SomeSubstitutionsType = True,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        ensure_argument_type(period, [*SomeSubstitutionsType_types_tuple, float], 'period', 'TimerAction')
        ensure_argument_type(actions, collections.abc.Iterable, 'actions', 'TimerAction')
        if isinstance(period, str):
            period = float(period)
            warnings.warn(
                "The parameter 'period' must be a float or substitution,passing a string literal was deprecated",
                stacklevel=2)
        self.__period = type_utils.normalize_typed_substitution(period, float)
        self.__actions = actions
        self.__context_locals: dict[str, Any] = {}
        self._completed_future: asyncio.Future | None = None
        self.__canceled = False
        self._canceled_future: asyncio.Future | None = None
        self.__cancel_on_shutdown = type_utils.normalize_typed_substitution(cancel_on_shutdown, bool)
        self.__logger = launch_logging.get_logger('launch.actions.timer_action')

    async def _wait_to_fire_event(self, context: LaunchContext) -> None:
        period = type_utils.perform_typed_substitution(context, self.__period, float)
        await asyncio.wait([self._canceled_future], timeout=period)
        if not self._canceled_future.done():
            await context.emit_event(TimerEvent(timer_action=self))
        self._completed_future.set_result(None)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        _, kwargs = super().parse(entity, parser)
        kwargs['period'] = parser.parse_if_substitutions(
            entity.get_attr('period', data_type=float, can_be_str=True))
        kwargs['actions'] = [parser.parse_action(child) for child in entity.children]
        cancel_on_shutdown = entity.get_attr('cancel_on_shutdown', optional=True, data_type=bool, can_be_str=True)
        if cancel_on_shutdown is not None:
            kwargs['cancel_on_shutdown'] = parser.parse_if_substitutions(cancel_on_shutdown)
        return cls, kwargs

    @property
    def period(self):
        return self.__period

    @property
    def actions(self):
        return self.__actions

    def describe(self) -> str:
        return f'TimerAction(period={self.__period}, actions=<actions>)'

    def describe_conditional_sub_entities(self) -> list[tuple[str, Iterable[LaunchDescriptionEntity]]]:
        return [(f'{self.__period} seconds pass without being canceled', self.__actions)]

    def handle(self, context: LaunchContext) -> SomeEntitiesType | None:
        """The actions to yield now that the timer fired, with the locals of when it started."""
        context.extend_locals(self.__context_locals)
        return self.__actions

    def cancel(self) -> None:
        """Cancel the timer; harmless when it already fired, was canceled, or has not started.

        Call it from the launch's loop (not thread-safe).
        """
        self.__canceled = True
        if self._canceled_future is not None and not self._canceled_future.done():
            self._canceled_future.set_result(True)

    def execute(self, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        loop = context.asyncio_loop
        self._completed_future = loop.create_future()
        self._canceled_future = loop.create_future()
        if self.__canceled:
            self.__logger.debug(f'timer {self} not waiting because it was canceled before being executed')
            self._completed_future.set_result(None)
            return None
        if not hasattr(context, _INSTALLED):
            context.register_event_handler(EventHandler(
                matcher=lambda event: is_a_subclass(event, TimerEvent),
                entities=OpaqueFunction(function=lambda context: context.locals.event.timer_action.handle(context)),
            ))
            setattr(context, _INSTALLED, True)
        self.__context_locals = dict(context.get_locals_as_dict())
        loop.create_task(self._wait_to_fire_event(context))
        if type_utils.perform_typed_substitution(context, self.__cancel_on_shutdown, bool):
            context.register_event_handler(EventHandler(
                matcher=lambda event: is_a_subclass(event, Shutdown),
                entities=OpaqueFunction(function=lambda context: self.cancel()),
            ))
        return None

    def get_asyncio_future(self) -> asyncio.Future | None:
        return self._completed_future
