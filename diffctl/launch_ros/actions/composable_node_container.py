"""ComposableNodeContainer (`node_container`): a container process, and the composable nodes to load into
it once it runs (a LoadComposableNodes the container returns from its execute)."""

from __future__ import annotations

from typing import Any

from diffctl.launch.action import Action
from diffctl.launch.frontend import Entity, Parser, expose_action
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType

from ..descriptions import ComposableNode
from .node import Node


@expose_action("node_container")
class ComposableNodeContainer(Node):
    """A Node that is a component container (`rclcpp_components component_container` runs diffctl's);
    `name` and `namespace` are required, as the load service is found by them."""

    def __init__(
        self,
        *,
        name: SomeSubstitutionsType,
        namespace: SomeSubstitutionsType,
        composable_node_descriptions: list[ComposableNode] | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(name=name, namespace=namespace, **kwargs)
        self.__composable_node_descriptions = composable_node_descriptions

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """A `node`, with `composable_node` children."""
        _, kwargs = super().parse(entity, parser)
        children = entity.get_attr("composable_node", data_type=list[Entity], optional=True)
        if children is not None:
            kwargs["composable_node_descriptions"] = []
            for child in children:
                description_cls, description_kwargs = ComposableNode.parse(parser, child)
                kwargs["composable_node_descriptions"].append(description_cls(**description_kwargs))
        return cls, kwargs

    def execute(self, context: LaunchContext) -> list[Action] | None:
        """Start the container; load the descriptions whose condition holds once it answers."""
        wanted = [
            d
            for d in self.__composable_node_descriptions or ()
            if d.condition() is None or d.condition().evaluate(context)
        ]
        actions = super().execute(context) or []
        if wanted:
            from .load_composable_nodes import LoadComposableNodes

            actions = [*actions, LoadComposableNodes(composable_node_descriptions=wanted, target_container=self)]
        return actions or None
