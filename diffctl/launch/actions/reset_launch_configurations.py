"""`ResetLaunchConfigurations`, `<reset>` with `<keep name=… value=…/>` children."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .._private.markup import kept_configurations
from ..action import Action
from ..frontend.expose import expose_action
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from ..frontend.entity import Entity
    from ..frontend.parser import Parser
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_action('reset')
class ResetLaunchConfigurations(Action):
    """Forgets every launch configuration but those of `launch_configurations` (name → value).

    The kept values are performed first, so they may read the configurations being forgotten.
    """

    def __init__(
        self,
        launch_configurations: dict[SomeSubstitutionsType, SomeSubstitutionsType] | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        self._kept = launch_configurations or {}

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        _, kwargs = super().parse(entity, parser)
        kept = kept_configurations(entity, parser)
        if kept is not None:
            kwargs['launch_configurations'] = kept
        return cls, kwargs

    def execute(self, context: LaunchContext) -> None:
        def text(value: SomeSubstitutionsType) -> str:
            return perform_substitutions(context, normalize_to_list_of_substitutions(value))

        survivors = {text(name): text(value) for name, value in self._kept.items()}
        table = context.launch_configurations
        table.clear()
        table.update(survivors)
