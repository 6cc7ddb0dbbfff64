"""`PopLaunchConfigurations`: Restore the launch configurations saved by the last `PushLaunchConfigurations`."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..action import Action

if TYPE_CHECKING:
    from ..launch_context import LaunchContext


class PopLaunchConfigurations(Action):
    """Restore the launch configurations saved by the last `PushLaunchConfigurations`."""

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)

    def execute(self, context: LaunchContext) -> None:
        context._pop_launch_configurations()
