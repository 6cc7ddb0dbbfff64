"""`Condition`: a predicate on the launch context deciding whether an action runs."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .launch_context import LaunchContext


class Condition:
    """Wraps `predicate(context) -> bool`; without a predicate the condition is false."""

    def __init__(self, *, predicate: Callable[[LaunchContext], bool] | None = None) -> None:
        self._predicate = predicate

    def describe(self) -> str:
        """Human-readable form of the condition."""
        return self.__repr__()

    def evaluate(self, context: LaunchContext) -> bool:
        """True when the action guarded by this condition should run."""
        predicate = self._predicate
        return False if predicate is None else predicate(context)
