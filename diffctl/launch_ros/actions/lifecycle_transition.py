"""LifecycleTransition: walk named lifecycle nodes through a list of transitions, one after the other.

For each node, the first ChangeState is emitted at once; each next one when the node reports the goal
state of the previous transition (a one-shot OnStateTransition). A node that goes to `errorprocessing` has
its remaining transitions dropped; so does one that completed the list.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterable
from typing import Any, ClassVar

import diffctl.launch.logging
from diffctl.launch.action import Action
from diffctl.launch.actions import EmitEvent, OpaqueFunction, RegisterEventHandler
from diffctl.launch.event_handler import EventHandler
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType
from diffctl.launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

from ..event_handlers import OnStateTransition
from ..events.lifecycle import ChangeState, StateTransition
from ..events.matchers import matches_node_name

LOGGER_NAME = "launch_ros.actions.lifecycle_transition"


def _fqn(node_name: str) -> str:
    return node_name if node_name.startswith("/") else f"/{node_name}"


def match_node_name_start_goal(node_name: str, start_state: str, goal_state: str) -> Callable[[Any], bool]:
    """A matcher of the StateTransition of node `node_name` from `start_state` to `goal_state`."""
    fqn = _fqn(node_name)
    return lambda event: (
        isinstance(event, StateTransition)
        and event.action.node_name == fqn
        and event.goal_state == goal_state
        and event.start_state == start_state
    )


def match_node_name_goal(node_name: str, goal_state: str) -> Callable[[Any], bool]:
    """A matcher of a StateTransition of node `node_name` to `goal_state`."""
    fqn = _fqn(node_name)
    return lambda event: (
        isinstance(event, StateTransition) and event.action.node_name == fqn and event.goal_state == goal_state
    )


class LifecycleTransition(Action):
    """Make `transition_ids` (lifecycle_msgs/msg/Transition ids, in order) of each of `lifecycle_node_names`."""

    # transition id → the labels of its transition state and of the state it ends in
    transition_targets: ClassVar[dict[int, dict[str, str]]] = {
        1: {"start_state": "configuring", "goal_state": "inactive"},
        2: {"start_state": "cleaningup", "goal_state": "unconfigured"},
        3: {"start_state": "activating", "goal_state": "active"},
        4: {"start_state": "deactivating", "goal_state": "inactive"},
        5: {"start_state": "shuttingdown", "goal_state": "finalized"},
        6: {"start_state": "shuttingdown", "goal_state": "finalized"},
        7: {"start_state": "shuttingdown", "goal_state": "finalized"},
    }

    def __init__(
        self,
        *,
        lifecycle_node_names: Iterable[SomeSubstitutionsType],
        transition_ids: Iterable[int | SomeSubstitutionsType],
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        names, ids = list(lifecycle_node_names), list(transition_ids)
        if not ids:
            raise ValueError("No transition_ids provided.")
        if not names:
            raise ValueError("No lifecycle_node_names provided.")
        self.__lifecycle_node_names = [normalize_to_list_of_substitutions(n) for n in names]
        self.__transition_ids = [normalize_to_list_of_substitutions(str(t) if isinstance(t, int) else t) for t in ids]
        self.__event_handlers: dict[str, list[EventHandler]] = {}
        self.__logger = diffctl.launch.logging.get_logger(LOGGER_NAME)

    def _remove_event_handlers(self, context: LaunchContext, node_name: str, reason: str | None = None) -> None:
        """Unregister what is left of a node's chain (handlers already gone are skipped)."""
        if reason is not None:
            self.__logger.info(f"Stopping transitions for {node_name} because '{reason}'")
        for handler in self.__event_handlers[node_name]:
            try:
                context.unregister_event_handler(handler)
            except ValueError:
                pass

    def execute(self, context: LaunchContext) -> list[Action] | None:
        """The handlers of each step and the first ChangeState of each node (the error handlers are
        registered at once)."""
        names = [perform_substitutions(context, n) for n in self.__lifecycle_node_names]
        ids: list[int] = []
        for text in (perform_substitutions(context, t) for t in self.__transition_ids):
            try:
                ids.append(int(text))
            except ValueError:
                raise ValueError(f"expected integer for lifecycle transition, got {text}") from None
        emits = {
            name: [
                EmitEvent(event=ChangeState(lifecycle_node_matcher=matches_node_name(name), transition_id=tid))
                for tid in ids
            ]
            for name in names
        }
        for name in names:
            self.__event_handlers[name] = []
        actions: list[Action] = []
        for step, tid in enumerate(ids, start=1):
            target = self.transition_targets[tid]
            for name in names:
                then: list[Action] = (
                    [emits[name][step]]
                    if step < len(ids)
                    else [OpaqueFunction(function=functools.partial(self._remove_event_handlers, node_name=name))]
                )
                handler = OnStateTransition(
                    matcher=match_node_name_start_goal(name, target["start_state"], target["goal_state"]),
                    entities=then,
                    handle_once=True,
                )
                self.__event_handlers[name].append(handler)
                actions.append(RegisterEventHandler(event_handler=handler))
        for name in names:
            on_error = EventHandler(
                matcher=match_node_name_goal(name, "errorprocessing"),
                entities=[
                    OpaqueFunction(
                        function=functools.partial(
                            self._remove_event_handlers, node_name=name, reason="error occured during transitions"
                        )
                    )
                ],
                handle_once=True,
            )
            self.__event_handlers[name].append(on_error)
            context.register_event_handler(on_error)
        actions.extend(emits[name][0] for name in names)
        return actions
