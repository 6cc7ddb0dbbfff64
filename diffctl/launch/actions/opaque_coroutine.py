"""`OpaqueCoroutine`: a coroutine run on the launch's loop, as a task the launch waits for."""

from __future__ import annotations

import asyncio
import collections.abc
from collections.abc import Awaitable, Callable, Iterable
from typing import TYPE_CHECKING, Any

from ..action import Action
from ..event_handlers.on_shutdown import OnShutdown
from ..utilities.ensure_argument_type_impl import ensure_argument_type

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..launch_description_entity import LaunchDescriptionEntity


class OpaqueCoroutine(Action):
    """Starts `coroutine(context, *args, **kwargs)` (without `context` if `ignore_context`) as a task.

    The launch is not idle while the task runs; a shutdown cancels it.
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
        for value, accepted, argument in (
            (args, (collections.abc.Iterable, type(None)), 'args'),
            (kwargs, (dict, type(None)), 'kwargs'),
            (ignore_context, bool, 'ignore_context'),
        ):
            ensure_argument_type(value, accepted, argument, 'OpaqueCoroutine')
        self._make = coroutine
        self._positional = tuple(args or ())
        self._named = dict(kwargs or {})
        self._with_context = not ignore_context
        self._task: asyncio.Task | None = None

    def execute(self, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        leading = (context,) if self._with_context else ()
        self._task = context.asyncio_loop.create_task(self._make(*leading, *self._positional, **self._named))
        task = self._task

        def stop(event: Any, context: LaunchContext) -> None:
            task.cancel()

        context.register_event_handler(OnShutdown(on_shutdown=stop))
        return None

    def get_asyncio_future(self) -> asyncio.Future | None:
        return self._task
