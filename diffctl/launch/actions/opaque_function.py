"""`OpaqueFunction`: Python code run while the launch is being visited."""

from __future__ import annotations

import collections.abc
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any

from ..action import Action
from ..utilities.ensure_argument_type_impl import ensure_argument_type

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..launch_description_entity import LaunchDescriptionEntity


class OpaqueFunction(Action):
    """Calls `function(context, *args, **kwargs)` when executed; the entities it returns are visited next.

    It runs on the launch's loop, so it must not block.
    """

    def __init__(
        self,
        *,
        function: Callable,
        args: Iterable[Any] | None = None,
        kwargs: dict[str, Any] | None = None,
        **left_over_kwargs: Any,
    ) -> None:
        super().__init__(**left_over_kwargs)
        if not callable(function):
            raise TypeError(f"OpaqueFunction expected a callable for 'function', got '{type(function)}'")
        ensure_argument_type(args, (collections.abc.Iterable, type(None)), 'args', 'OpaqueFunction')
        ensure_argument_type(kwargs, (dict, type(None)), 'kwargs', 'OpaqueFunction')
        self._call = (function, tuple(args or ()), dict(kwargs or {}))

    def execute(self, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        function, positional, named = self._call
        return function(context, *positional, **named)
