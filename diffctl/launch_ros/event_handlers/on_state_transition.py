"""OnStateTransition: entities for the StateTransition events of lifecycle nodes, filtered by node and labels."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from diffctl.launch.event import Event
from diffctl.launch.event_handler import EventHandler
from diffctl.launch.some_entities_type import SomeEntitiesType
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType

from ..actions.lifecycle_node import LifecycleNode
from ..events.lifecycle import StateTransition


class OnStateTransition(EventHandler):
    """Handle StateTransition events of `target_lifecycle_node` (any when None) whose `transition`,
    `start_state` and `goal_state` labels equal those given (None: any). A `matcher` replaces all of these."""

    def __init__(
        self,
        *,
        entities: SomeEntitiesType,
        target_lifecycle_node: LifecycleNode | None = None,
        transition: SomeSubstitutionsType | None = None,
        start_state: SomeSubstitutionsType | None = None,
        goal_state: SomeSubstitutionsType | None = None,
        matcher: Callable[[Event], bool] | None = None,
        **kwargs: Any,
    ) -> None:
        if not isinstance(target_lifecycle_node, (LifecycleNode, type(None))):
            raise RuntimeError("OnStateTransition requires a 'LifecycleNode' action as the target")
        wanted = {"transition": transition, "start_state": start_state, "goal_state": goal_state}

        def default_matcher(event: Event) -> bool:
            if not isinstance(event, StateTransition):
                return False
            if target_lifecycle_node is not None and event.action != target_lifecycle_node:
                return False
            return all(value is None or getattr(event, key) == value for key, value in wanted.items())

        super().__init__(matcher=matcher if matcher is not None else default_matcher, entities=entities, **kwargs)
        self.__target_lifecycle_node = target_lifecycle_node

    @property
    def handler_description(self) -> str:
        return "<actions>"

    @property
    def matcher_description(self) -> str:
        if self.__target_lifecycle_node is None:
            return "event == StateTransition"
        return f"event == StateTransition and event.action == LifecycleNode({hex(id(self.__target_lifecycle_node))})"
