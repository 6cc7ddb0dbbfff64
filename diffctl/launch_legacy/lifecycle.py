"""launch_ros's managed nodes: LifecycleNode, the ChangeState and StateTransition events, OnStateTransition.

A LifecycleNode is a Node that, once started, reports its transitions (`<node>/transition_event`) as
StateTransition events and takes ChangeState events by calling `<node>/change_state`. The engine knows
processes, not the bus: both go through a `LifecycleServices` object that the CLI layer gives the supervisor
(diffctl/cli/launch_lifecycle.py, on the rclpy-compatible client), whose callbacks arrive on other threads and
are posted to the launch's own.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol

from diffctl.errors import LaunchError
from diffctl.launch_legacy.actions import Action
from diffctl.launch_legacy.event_handlers import BaseEventHandler
from diffctl.launch_legacy.events import Event
from diffctl.launch_legacy.process_actions import Node
from diffctl.launch_legacy.registry import register

if TYPE_CHECKING:
    from diffctl.launch_legacy.context import Scope


class LifecycleServices(Protocol):
    """The bus side of managed nodes (injected by the CLI layer)."""

    def watch_transitions(self, node_fqn: str, on_transition: Callable[[str, str, str, Any], None]) -> None:
        """Call on_transition(transition, start_state, goal_state, msg) for each TransitionEvent of the node."""

    def change_state(self, node_fqn: str, transition_id: int, done: Callable[[bool, str], None]) -> None:
        """Ask the node for a transition (waiting for its service); done(success, error) when answered."""


class ChangeState(Event):
    """launch_ros.events.lifecycle.ChangeState: ask the matched lifecycle nodes for a transition."""

    name = "launch_ros.events.lifecycle.ChangeState"

    def __init__(self, *, lifecycle_node_matcher: Callable[[Any], bool], transition_id: int) -> None:
        if not callable(lifecycle_node_matcher):
            raise LaunchError("ChangeState: lifecycle_node_matcher must be a callable, e.g. matches_action(node)")
        self.lifecycle_node_matcher = lifecycle_node_matcher
        self.transition_id = int(transition_id)


class StateTransition(Event):
    """launch_ros.events.lifecycle.StateTransition: a lifecycle node went through a transition."""

    name = "launch_ros.events.lifecycle.StateTransition"

    def __init__(self, *, action: Any, msg: Any, transition: str, start_state: str, goal_state: str) -> None:
        self.action = action
        self.msg = msg
        self.transition = transition
        self.start_state = start_state
        self.goal_state = goal_state


def matches_node_name(node_name: str) -> Callable[[Any], bool]:
    """A matcher of the lifecycle node with this fully qualified name (`/ns/name`), as launch_ros's."""
    fqn = node_name if node_name.startswith("/") else f"/{node_name}"  # as launch_ros's: `talker` is `/talker`
    return lambda action: getattr(action, "node_name", None) == fqn


class OnStateTransition(BaseEventHandler):
    """Entities (or a callable) for StateTransition events, filtered by node and transition / state labels."""

    kind = "state"

    def __init__(
        self,
        *,
        entities: Any = None,
        target_lifecycle_node: Any = None,
        transition: str | None = None,
        start_state: str | None = None,
        goal_state: str | None = None,
        matcher: Callable[[Any], bool] | None = None,
        handle_once: bool = False,
    ) -> None:
        fn = entities if callable(entities) and not isinstance(entities, Action) else None
        super().__init__(entities=None if fn is not None else entities, handle_once=handle_once)
        self.callable = fn
        self.target = target_lifecycle_node
        self.labels = {"transition": transition, "start_state": start_state, "goal_state": goal_state}
        self.user_matcher = matcher

    def matches(self, event: Any) -> bool:
        if not isinstance(event, StateTransition):
            return False
        if self.user_matcher is not None and not self.user_matcher(event):
            return False
        if self.target is not None and event.action is not self.target:
            return False
        return all(want is None or getattr(event, key) == want for key, want in self.labels.items())


class _ChangeStateHandler(BaseEventHandler):
    """Registered by each executed LifecycleNode: ChangeState events that match it call its service."""

    kind = "change_state"

    def __init__(self, node: LifecycleNode, fqn: str) -> None:
        super().__init__()
        self.node, self.fqn = node, fqn

    def matches(self, event: Any) -> bool:
        return isinstance(event, ChangeState) and bool(event.lifecycle_node_matcher(self.node))

    def handle(self, event: Any, context: Scope) -> list[Action] | None:
        engine = context.engine
        services = engine.lifecycle()
        if services is None:
            raise LaunchError("lifecycle transitions need the bus, which this launch was not given")

        def done(ok: bool, error: str) -> None:
            if not ok:
                engine.post_log(
                    "ERROR",
                    f"Failed to make transition '{event.transition_id}' for LifecycleNode '{self.fqn}': {error}",
                )

        services.change_state(self.fqn, event.transition_id, done)
        return None


@register
class LifecycleNode(Node):
    """A managed node (`LifecycleNode(name=…, namespace=…, …)`, tag `lifecycle_node`): a Node whose transitions
    become events and which takes ChangeState events."""

    frontend_tags = ("lifecycle_node",)

    def __init__(self, *, name: Any, namespace: Any, **kw: Any) -> None:
        super().__init__(name=name, namespace=namespace, **kw)

    def execute(self, context: Scope) -> list[Action] | None:
        result = super().execute(context)
        fqn = self._fqn or ""
        engine = context.engine
        if not engine.dry and not context.is_shutdown:
            context.register_event_handler(_ChangeStateHandler(self, fqn))

            def on_transition(transition: str, start: str, goal: str, msg: Any) -> None:
                engine.post_event(
                    StateTransition(action=self, msg=msg, transition=transition, start_state=start, goal_state=goal)
                )

            def watch() -> None:  # once the launch runs (the first visit starts nothing, the bus included)
                services = engine.lifecycle()
                if services is not None:
                    services.watch_transitions(fqn, on_transition)

            engine.defer(watch)
        return result
