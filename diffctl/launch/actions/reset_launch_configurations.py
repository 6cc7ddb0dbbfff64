"""`ResetLaunchConfigurations` (`<reset>`): clear the launch configurations, keeping some if asked."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..action import Action
from ..frontend.entity import Entity
from ..frontend.expose import expose_action
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from ..frontend.parser import Parser
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


def parse_keeps(entity: Entity, parser: Parser) -> dict | None:
    """The `<keep name=… value=…/>` children of an entity as a {name: value} dict, or None."""
    keeps = entity.get_attr('keep', data_type=list[Entity], optional=True)
    if keeps is None:
        return None
    result = {
        tuple(parser.parse_substitution(e.get_attr('name'))): parser.parse_substitution(e.get_attr('value'))
        for e in keeps
    }
    for e in keeps:
        e.assert_entity_completely_parsed()
    return result


@expose_action('reset')
class ResetLaunchConfigurations(Action):
    """Clears the launch configurations, then sets `launch_configurations` (evaluated before clearing)."""

    def __init__(
        self,
        launch_configurations: dict[SomeSubstitutionsType, SomeSubstitutionsType] | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        self.__launch_configurations = launch_configurations

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        _, kwargs = super().parse(entity, parser)
        keeps = parse_keeps(entity, parser)
        if keeps is not None:
            kwargs['launch_configurations'] = keeps
        return cls, kwargs

    def execute(self, context: LaunchContext) -> None:
        kept = {}
        for name, value in (self.__launch_configurations or {}).items():
            kept[perform_substitutions(context, normalize_to_list_of_substitutions(name))] = \
                perform_substitutions(context, normalize_to_list_of_substitutions(value))
        context.launch_configurations.clear()
        context.launch_configurations.update(kept)
