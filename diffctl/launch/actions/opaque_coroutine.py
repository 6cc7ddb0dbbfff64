"""`OpaqueCoroutine`: run a coroutine function on the launch's loop."""

from __future__ import annotations

import asyncio
import collections.abc
from collections.abc import Awaitable, Callable, Iterable
from typing import TYPE_CHECKING, Any

from ..action import Action
from ..event_handlers.on_shutdown import OnShutdown
from ..utilities.ensure_argument_type_impl import ensure_argument_type

if TYPE_CHECKING:
    from ..event import Event
    from ..launch_context import LaunchContext
    from ..launch_description_entity import LaunchDescriptionEntity


class OpaqueCoroutine(Action):
    """Starts `coroutine(context, *args, **kwargs)` as a task (without `context` when `ignore_context`).

    The launch waits for the task before it is idle; shutting down cancels it.
    """

    def __init__(
        self,
        *,
        coroutine: Callable[..., Awaitable[None]],
        args: Iterable[Any] | None = None,
        kwargs: dict[str, Any] | None = None,
        ignore_context: bool = False,
        **left_over_kwargs: Any,
    ) -> None:
        super().__init__(**left_over_kwargs)
        if not asyncio.iscoroutinefunction(coroutine):
            raise TypeError(
                f"OpaqueCoroutine expected a coroutine function for 'coroutine', got '{type(coroutine)}'")
        ensure_argument_type(args, (collections.abc.Iterable, type(None)), 'args', 'OpaqueCoroutine')
        ensure_argument_type(kwargs, (dict, type(None)), 'kwargs', 'OpaqueCoroutine')
        ensure_argument_type(ignore_context, bool, 'ignore_context', 'OpaqueCoroutine')
        self.__coroutine = coroutine
        self.__args = args if args is not None else []
        self.__kwargs = kwargs if kwargs is not None else {}
        self.__ignore_context = ignore_context
        self.__future: asyncio.Future | None = None

    def __on_shutdown(self, event: Event, context: LaunchContext) -> None:
        if self.__future is not None:
            self.__future.cancel()
        return None

    def execute(self, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        args = list(self.__args) if self.__ignore_context else [context, *self.__args]
        self.__future = context.asyncio_loop.create_task(self.__coroutine(*args, **self.__kwargs))
        context.register_event_handler(OnShutdown(on_shutdown=self.__on_shutdown))
        return None

    def get_asyncio_future(self) -> asyncio.Future | None:
        return self.__future
