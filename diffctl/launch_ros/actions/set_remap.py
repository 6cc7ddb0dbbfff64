"""SetRemap (`set_remap`): a remapping rule for every node after it in the same scope."""

from __future__ import annotations

from typing import Any

from diffctl.launch.action import Action
from diffctl.launch.frontend import Entity, Parser, expose_action
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType
from diffctl.launch.substitution import Substitution
from diffctl.launch.utilities import normalize_to_list_of_substitutions, perform_substitutions


@expose_action("set_remap")
class SetRemap(Action):
    """Append `(src, dst)` to the `ros_remaps` launch configuration: each Node after it in the scope passes
    it as `-r src:=dst` before its own remappings (a scoped group drops it)."""

    def __init__(self, src: SomeSubstitutionsType, dst: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__src = normalize_to_list_of_substitutions(src)
        self.__dst = normalize_to_list_of_substitutions(dst)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        _, kwargs = super().parse(entity, parser)
        kwargs["src"] = parser.parse_substitution(entity.get_attr("from"))
        kwargs["dst"] = parser.parse_substitution(entity.get_attr("to"))
        return cls, kwargs

    @property
    def src(self) -> list[Substitution]:
        return self.__src

    @property
    def dst(self) -> list[Substitution]:
        return self.__dst

    def execute(self, context: LaunchContext) -> None:
        rule = (perform_substitutions(context, self.__src), perform_substitutions(context, self.__dst))
        remaps = context.launch_configurations.get("ros_remaps", [])
        remaps.append(rule)
        context.launch_configurations["ros_remaps"] = remaps
