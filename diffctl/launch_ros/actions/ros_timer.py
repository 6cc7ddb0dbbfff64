"""RosTimer (`ros_timer`): a TimerAction counted on the ROS clock of the launch's node, so on simulated time
after SetUseSimTime(True)."""

from __future__ import annotations

import asyncio
import collections.abc
from collections.abc import Iterable
from typing import Any

from diffctl.launch.actions import TimerAction
from diffctl.launch.events import TimerEvent
from diffctl.launch.frontend import Entity, Parser, expose_action
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.launch_description_entity import LaunchDescriptionEntity
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType, SomeSubstitutionsType_types_tuple
from diffctl.launch.utilities import ensure_argument_type, type_utils

from ..ros_adapters import get_ros_node


@expose_action("ros_timer")
class ROSTimer(TimerAction):
    """Run `actions` once `period` seconds of ROS time have passed, unless cancelled (one shot)."""

    def __init__(
        self, *, period: float | SomeSubstitutionsType, actions: Iterable[LaunchDescriptionEntity], **kwargs: Any
    ) -> None:
        super().__init__(period=period, actions=actions, **kwargs)
        ensure_argument_type(period, [*SomeSubstitutionsType_types_tuple, float], "period", "ROSTimer")
        ensure_argument_type(actions, collections.abc.Iterable, "actions", "ROSTimer")
        self.__period = type_utils.normalize_typed_substitution(period, float)
        self.__timer_future: asyncio.Future | None = None

    def __fire(self) -> None:
        if self.__timer_future is not None and not self.__timer_future.done():
            self.__timer_future.set_result(True)

    async def _wait_to_fire_event(self, context: LaunchContext) -> None:
        loop = context.asyncio_loop
        period_s = type_utils.perform_typed_substitution(context, self.__period, float)
        node = get_ros_node(context)
        timer = node.create_timer(period_s, lambda: loop.call_soon_threadsafe(self.__fire))
        try:
            await asyncio.wait([self._canceled_future, self.__timer_future], return_when=asyncio.FIRST_COMPLETED)
        finally:
            node.destroy_timer(timer)  # one shot: it must not fire (and call into the loop) again
        if not self._canceled_future.done():
            await context.emit_event(TimerEvent(timer_action=self))
        self._completed_future.set_result(None)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        _, kwargs = super().parse(entity, parser)
        kwargs["period"] = parser.parse_if_substitutions(entity.get_attr("period", data_type=float, can_be_str=True))
        kwargs["actions"] = [parser.parse_action(child) for child in entity.children]
        return cls, kwargs

    def describe(self) -> str:
        return f"ROSTimer(period={self.__period}, actions=<actions>)"

    def execute(self, context: LaunchContext) -> Any:
        self.__timer_future = context.asyncio_loop.create_future()
        return super().execute(context)
