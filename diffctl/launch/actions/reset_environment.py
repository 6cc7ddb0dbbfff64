"""`ResetEnvironment` (`<reset_env/>`): back to the environment the launch started with."""

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
    """Undoes every environment change made by earlier actions (to `os.environ` as the context found it)."""

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        _, kwargs = super().parse(entity, parser)
        return cls, kwargs

    def execute(self, context: LaunchContext) -> None:
        context._reset_environment()
