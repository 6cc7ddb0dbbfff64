"""`PopLaunchConfigurations`: one half of a scope (GroupAction brackets its actions with such pairs)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..action import Action

if TYPE_CHECKING:
    from ..launch_context import LaunchContext


class PopLaunchConfigurations(Action):
    """Puts back the launch configurations the last PushLaunchConfigurations saved (an error without one)."""

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)

    def execute(self, context: LaunchContext) -> None:
        context._restore('launch_configurations')
