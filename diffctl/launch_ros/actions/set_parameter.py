"""SetParameter (`set_parameter`): a parameter for every node started after it in the same scope."""

from __future__ import annotations

from typing import Any

from diffctl.launch.action import Action
from diffctl.launch.frontend import Entity, Parser, expose_action
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType
from diffctl.launch.utilities import normalize_to_list_of_substitutions

from ..parameters_type import ParameterName, ParameterValue, SomeParameterValue
from ..utilities.evaluate_parameters import evaluate_parameter_dict
from ..utilities.normalize_parameters import normalize_parameter_dict


@expose_action("set_parameter")
class SetParameter(Action):
    """Append `(name, value)`, evaluated, to the `global_params` launch configuration: each Node after it in
    the scope passes it as `-p name:=value` before its own parameters (a scoped group drops it)."""

    def __init__(self, name: SomeSubstitutionsType, value: SomeParameterValue, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__param_dict = normalize_parameter_dict({tuple(normalize_to_list_of_substitutions(name)): value})

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        _, kwargs = super().parse(entity, parser)
        kwargs["name"] = parser.parse_substitution(entity.get_attr("name"))
        kwargs["value"] = parser.parse_substitution(entity.get_attr("value"))
        return cls, kwargs

    @property
    def name(self) -> ParameterName:
        return next(iter(self.__param_dict))

    @property
    def value(self) -> ParameterValue:
        return next(iter(self.__param_dict.values()))

    def execute(self, context: LaunchContext) -> None:
        evaluated = evaluate_parameter_dict(context, self.__param_dict)
        params = context.launch_configurations.get("global_params", [])
        params.extend(evaluated.items())
        context.launch_configurations["global_params"] = params
