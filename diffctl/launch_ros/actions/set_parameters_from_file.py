"""SetParametersFromFile (`set_parameters_from_file`): a parameters file for every node after it in the scope."""

from __future__ import annotations

from typing import Any

from diffctl.launch.action import Action
from diffctl.launch.frontend import Entity, Parser, expose_action
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType
from diffctl.launch.utilities import normalize_to_list_of_substitutions, perform_substitutions


@expose_action("set_parameters_from_file")
class SetParametersFromFile(Action):
    """Append a YAML file to the `global_params` launch configuration: each Node after it in the scope
    passes it as `--params-file` before its own parameters (a scoped group drops it)."""

    def __init__(self, filename: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self._input_file = normalize_to_list_of_substitutions(filename)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        _, kwargs = super().parse(entity, parser)
        kwargs["filename"] = parser.parse_substitution(entity.get_attr("filename"))
        return cls, kwargs

    def execute(self, context: LaunchContext) -> None:
        filename = perform_substitutions(context, self._input_file)
        params = context.launch_configurations.get("global_params", [])
        params.append(filename)
        context.launch_configurations["global_params"] = params
