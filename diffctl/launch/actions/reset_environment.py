"""`ResetEnvironment`, `<reset_env/>`: the environment as it was when the launch began."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..action import Action
from ..frontend.expose import expose_action

if TYPE_CHECKING:
    from ..frontend.entity import Entity
    from ..frontend.parser import Parser
    from ..launch_context import LaunchContext


@expose_action('reset_env')
class ResetEnvironment(Action):
    """Drops every environment change made since the launch context was created."""

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        return cls, super().parse(entity, parser)[1]

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)

    def execute(self, context: LaunchContext) -> None:
        context._restore_first_environment()
