"""`TimerAction`, `<timer period=…>`: actions visited after a delay, unless canceled before."""

from __future__ import annotations

import asyncio
import collections.abc
import warnings
import weakref
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from .. import logging as launch_logging
from .._private.markup import typed_attribute
from ..action import Action
from ..event_handler import BaseEventHandler, EventHandler, _takes_only
from ..events.shutdown import Shutdown
from ..events.timer_event import TimerEvent
from ..frontend.expose import expose_action
from ..some_substitutions_type import SomeSubstitutionsType_types_tuple
from ..utilities import type_utils
from ..utilities.ensure_argument_type_impl import ensure_argument_type
from .opaque_function import OpaqueFunction

if TYPE_CHECKING:
    from ..frontend.entity import Entity
    from ..frontend.parser import Parser
    from ..launch_context import LaunchContext
    from ..launch_description_entity import LaunchDescriptionEntity
    from ..some_entities_type import SomeEntitiesType
    from ..some_substitutions_type import SomeSubstitutionsType

# Contexts holding the one handler that hands every TimerEvent to the timer it names.
_DISPATCHING: weakref.WeakSet = weakref.WeakSet()


def _dispatcher() -> BaseEventHandler:
    return _takes_only(EventHandler(
        matcher=lambda event: isinstance(event, TimerEvent),
        entities=OpaqueFunction(function=lambda context: context.locals.event.timer_action.handle(context)),
    ), TimerEvent)


@expose_action('timer')
class TimerAction(Action):
    """After `period` seconds, visits `actions` with the locals the context had when the timer started.

    It fires once. `cancel()` before that stops it; with `cancel_on_shutdown` (the default) a launch
    shutdown cancels it, so that a pending timer does not keep the launch alive. `period` is performed
    when the wait begins, just after the timer is executed.

    Subclasses may replace `_wait_to_fire_event(context)` (launch_ros's RosTimer waits on ROS time): it
    must emit the TimerEvent unless `_canceled_future` is done, then complete `_completed_future`.
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
        self._delay = type_utils.normalize_typed_substitution(period, float)
        self._payload = actions
        self._stop_on_shutdown = type_utils.normalize_typed_substitution(cancel_on_shutdown, bool)
        self._locals_at_start: dict[str, Any] = {}
        self._cancel_requested = False
        # the hooks of subclasses: done when the wait ends, and when the timer is canceled
        self._completed_future: asyncio.Future | None = None
        self._canceled_future: asyncio.Future | None = None

    @property
    def period(self):
        return self._delay

    @property
    def actions(self):
        return self._payload

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        _, kwargs = super().parse(entity, parser)
        kwargs['period'] = typed_attribute(entity, parser, 'period', float, optional=False)
        kwargs['actions'] = [parser.parse_action(child) for child in entity.children]
        on_shutdown = typed_attribute(entity, parser, 'cancel_on_shutdown', bool, optional=True)
        if on_shutdown is not None:
            kwargs['cancel_on_shutdown'] = on_shutdown
        return cls, kwargs

    def describe(self) -> str:
        return f'TimerAction(period={self._delay}, actions=<actions>)'

    def describe_conditional_sub_entities(self) -> list[tuple[str, Iterable[LaunchDescriptionEntity]]]:
        return [(f'{self._delay} seconds pass without being canceled', self._payload)]

    async def _wait_to_fire_event(self, context: LaunchContext) -> None:
        seconds = type_utils.perform_typed_substitution(context, self._delay, float)
        await asyncio.wait([self._canceled_future], timeout=seconds)
        if not self._canceled_future.done():
            await context.emit_event(TimerEvent(timer_action=self))
        self._completed_future.set_result(None)

    def handle(self, context: LaunchContext) -> SomeEntitiesType | None:
        """The actions, now that the timer fired, in the locals of when it started."""
        context.extend_locals(self._locals_at_start)
        return self._payload

    def cancel(self) -> None:
        """Stop the timer. Harmless when it fired or was canceled already, or has not started yet.

        Not thread-safe: call it on the launch's loop.
        """
        self._cancel_requested = True
        pending = self._canceled_future
        if pending is not None and not pending.done():
            pending.set_result(True)

    def execute(self, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        loop = context.asyncio_loop
        self._completed_future, self._canceled_future = loop.create_future(), loop.create_future()
        if self._cancel_requested:
            launch_logging.get_logger('launch.actions.timer_action').debug(
                f'timer {self} not waiting because it was canceled before being executed')
            self._completed_future.set_result(None)
            return None
        if context not in _DISPATCHING:
            context.register_event_handler(_dispatcher())
            _DISPATCHING.add(context)
        self._locals_at_start = dict(context.get_locals_as_dict())
        loop.create_task(self._wait_to_fire_event(context))
        if type_utils.perform_typed_substitution(context, self._stop_on_shutdown, bool):
            context.register_event_handler(_takes_only(EventHandler(
                matcher=lambda event: isinstance(event, Shutdown),
                entities=OpaqueFunction(function=lambda context: self.cancel()),
            ), Shutdown))
        return None

    def get_asyncio_future(self) -> asyncio.Future | None:
        return self._completed_future
