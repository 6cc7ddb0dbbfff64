"""`PopEnvironment`: Restore the environment saved by the last `PushEnvironment`."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..action import Action

if TYPE_CHECKING:
    from ..launch_context import LaunchContext


class PopEnvironment(Action):
    """Restore the environment saved by the last `PushEnvironment`."""

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)

    def execute(self, context: LaunchContext) -> None:
        context._pop_environment()
