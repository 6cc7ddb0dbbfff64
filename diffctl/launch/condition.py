"""`Condition`: whether an action runs, decided when it is visited."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from ._private.ros_names import default_text

if TYPE_CHECKING:
    from .launch_context import LaunchContext


class Condition:
    """A yes/no question on the launch context, asked by `Action.visit` before executing.

    `predicate(context)` answers it; a condition made without one always says no.
    """

    def __repr__(self) -> str:
        return default_text(self)  # under ROS's module names, as ros2 launch --print shows it

    def __init__(self, *, predicate: Callable[[LaunchContext], bool] | None = None) -> None:
        self._test = predicate

    def describe(self) -> str:
        """Text for introspection (the object's repr unless a subclass says better)."""
        return repr(self)

    def evaluate(self, context: LaunchContext) -> bool:
        """The answer for `context`."""
        if self._test is None:
            return False
        return self._test(context)
