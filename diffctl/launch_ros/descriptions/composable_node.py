"""ComposableNode: what a container loads — a plugin of a package, with a name, namespace, parameters,
remappings and container-specific extra arguments."""

from __future__ import annotations

from typing import Any

from diffctl.launch.condition import Condition
from diffctl.launch.conditions import IfCondition, UnlessCondition
from diffctl.launch.frontend import Entity, Parser
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType
from diffctl.launch.substitution import Substitution
from diffctl.launch.utilities import normalize_to_list_of_substitutions

from ..parameters_type import Parameters, SomeParameters
from ..remap_rule_type import RemapRules, SomeRemapRules
from ..utilities import normalize_parameters, normalize_remap_rules


class ComposableNode:
    """A node for a container: `plugin` of `package` (for diffctl's container, a Python class: `module:Class`
    or an `rclpy_components` entry point name), loaded when `condition` holds."""

    def __init__(
        self,
        *,
        package: SomeSubstitutionsType,
        plugin: SomeSubstitutionsType,
        name: SomeSubstitutionsType | None = None,
        namespace: SomeSubstitutionsType | None = None,
        parameters: SomeParameters | None = None,
        remappings: SomeRemapRules | None = None,
        extra_arguments: SomeParameters | None = None,
        condition: Condition | None = None,
    ) -> None:
        self.__package = normalize_to_list_of_substitutions(package)
        self.__node_plugin = normalize_to_list_of_substitutions(plugin)
        self.__node_name = None if name is None else normalize_to_list_of_substitutions(name)
        self.__node_namespace = None if namespace is None else normalize_to_list_of_substitutions(namespace)
        self.__parameters = None if parameters is None else normalize_parameters(parameters)
        self.__remappings = list(normalize_remap_rules(remappings)) if remappings else None
        self.__extra_arguments = normalize_parameters(extra_arguments) if extra_arguments else None
        self.__condition = condition

    @classmethod
    def parse(cls, parser: Parser, entity: Entity) -> tuple[type, dict[str, Any]]:
        """`composable_node`: pkg, plugin, name, namespace, if/unless, param, remap, extra_arg (name, value)."""
        from ..actions.node import Node

        kwargs: dict[str, Any] = {
            "package": parser.parse_substitution(entity.get_attr("pkg")),
            "plugin": parser.parse_substitution(entity.get_attr("plugin")),
            "name": parser.parse_substitution(entity.get_attr("name")),
        }
        if_cond = entity.get_attr("if", optional=True)
        unless_cond = entity.get_attr("unless", optional=True)
        if if_cond is not None and unless_cond is not None:
            raise RuntimeError("if and unless conditions can't be used simultaneously")
        if if_cond is not None:
            kwargs["condition"] = IfCondition(predicate_expression=parser.parse_substitution(if_cond))
        if unless_cond is not None:
            kwargs["condition"] = UnlessCondition(predicate_expression=parser.parse_substitution(unless_cond))
        namespace = entity.get_attr("namespace", optional=True)
        if namespace is not None:
            kwargs["namespace"] = parser.parse_substitution(namespace)
        params = entity.get_attr("param", data_type=list[Entity], optional=True)
        if params is not None:
            kwargs["parameters"] = Node.parse_nested_parameters(params, parser)
        remaps = entity.get_attr("remap", data_type=list[Entity], optional=True)
        if remaps is not None:
            kwargs["remappings"] = [
                (parser.parse_substitution(r.get_attr("from")), parser.parse_substitution(r.get_attr("to")))
                for r in remaps
            ]
            for r in remaps:
                r.assert_entity_completely_parsed()
        extra = entity.get_attr("extra_arg", data_type=list[Entity], optional=True)
        if extra is not None:
            kwargs["extra_arguments"] = [
                {tuple(parser.parse_substitution(x.get_attr("name"))): parser.parse_substitution(x.get_attr("value"))}
                for x in extra
            ]
            for x in extra:
                x.assert_entity_completely_parsed()
        entity.assert_entity_completely_parsed()
        return cls, kwargs

    @property
    def package(self) -> list[Substitution]:
        return self.__package

    @property
    def node_plugin(self) -> list[Substitution]:
        return self.__node_plugin

    @property
    def node_name(self) -> list[Substitution] | None:
        return self.__node_name

    @property
    def node_namespace(self) -> list[Substitution] | None:
        return self.__node_namespace

    @property
    def parameters(self) -> Parameters | None:
        return self.__parameters

    @property
    def remappings(self) -> RemapRules | None:
        return self.__remappings

    @property
    def extra_arguments(self) -> Parameters | None:
        return self.__extra_arguments

    def condition(self) -> Condition | None:
        return self.__condition
