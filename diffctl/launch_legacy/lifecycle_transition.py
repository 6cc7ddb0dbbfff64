"""launch_ros's LifecycleTransition: walk lifecycle nodes, by name, through a list of transitions.

As launch_ros (jazzy) builds it: for each node a ChangeState event per transition; the first is emitted now,
each next one when the node reports the goal state of the previous (a one-shot OnStateTransition), the last
unregisters the rest; a node that goes to `errorprocessing` has its remaining transitions dropped. The calls
go through the lifecycle bridge the launch already has for ChangeState (diffctl/cli/launch_lifecycle.py).
"""

from __future__ import annotations

import functools
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from diffctl.errors import LaunchError
from diffctl.launch_legacy.actions import Action
from diffctl.launch_legacy.event_actions import EmitEvent, OpaqueFunction
from diffctl.launch_legacy.event_handlers import BaseEventHandler, RegisterEventHandler
from diffctl.launch_legacy.lifecycle import ChangeState, OnStateTransition, StateTransition, matches_node_name
from diffctl.launch_legacy.substitutions import SomeSubstitutions, normalize, perform

if TYPE_CHECKING:
    from diffctl.launch_legacy.context import Scope

# lifecycle_msgs/msg/Transition ids → the (start, goal) states of their transition event, as launch_ros's table.
TRANSITION_TARGETS: dict[int, tuple[str, str]] = {
    1: ("configuring", "inactive"),  # TRANSITION_CONFIGURE
    2: ("cleaningup", "unconfigured"),  # TRANSITION_CLEANUP
    3: ("activating", "active"),  # TRANSITION_ACTIVATE
    4: ("deactivating", "inactive"),  # TRANSITION_DEACTIVATE
    5: ("shuttingdown", "finalized"),  # TRANSITION_UNCONFIGURED_SHUTDOWN
    6: ("shuttingdown", "finalized"),  # TRANSITION_INACTIVE_SHUTDOWN
    7: ("shuttingdown", "finalized"),  # TRANSITION_ACTIVE_SHUTDOWN
}


def _fqn(node_name: str) -> str:
    return node_name if node_name.startswith("/") else f"/{node_name}"


def _reaches(node_name: str, goal: str, start: str | None = None) -> Any:
    fqn = _fqn(node_name)
    return lambda event: (
        isinstance(event, StateTransition)
        and getattr(event.action, "node_name", None) == fqn
        and event.goal_state == goal
        and (start is None or event.start_state == start)
    )


class LifecycleTransition(Action):
    def __init__(
        self,
        *,
        lifecycle_node_names: Iterable[SomeSubstitutions],
        transition_ids: Iterable[int | SomeSubstitutions],
        **kw: Any,
    ) -> None:
        super().__init__(**kw)
        names, ids = list(lifecycle_node_names), list(transition_ids)
        if not ids:
            raise LaunchError("LifecycleTransition: no transition_ids given")
        if not names:
            raise LaunchError("LifecycleTransition: no lifecycle_node_names given")
        self.node_names = [normalize(n) for n in names]
        self.transition_ids = [normalize(str(t) if isinstance(t, int) else t) for t in ids]
        self.handlers: dict[str, list[BaseEventHandler]] = {}

    def label(self) -> str:
        return "LifecycleTransition"

    def _remove_handlers(self, context: Scope, node_name: str, reason: str | None = None) -> None:
        if reason is not None and not context.engine.dry:
            context.engine.post_log("INFO", f"Stopping transitions for {node_name} because '{reason}'")
        for handler in self.handlers[node_name]:
            try:
                context.unregister_event_handler(handler)
            except ValueError:  # already gone (a one-shot that fired)
                pass

    def execute(self, context: Scope) -> list[Action] | None:
        names = [perform(n, context) for n in self.node_names]
        ids: list[int] = []
        for raw in (perform(t, context) for t in self.transition_ids):
            try:
                tid = int(raw)
            except ValueError:
                raise LaunchError(f"expected an integer transition id, got {raw!r}") from None
            if tid not in TRANSITION_TARGETS:
                raise LaunchError(
                    f"{tid} is not a lifecycle transition id",
                    hint="valid: 1 configure, 2 cleanup, 3 activate, 4 deactivate, 5-7 shutdown "
                    "(lifecycle_msgs.msg.Transition.TRANSITION_*)",
                )
            ids.append(tid)
        emits = {
            name: [
                EmitEvent(event=ChangeState(lifecycle_node_matcher=matches_node_name(name), transition_id=t))
                for t in ids
            ]
            for name in names
        }
        actions: list[Action] = []
        for i, tid in enumerate(ids, start=1):
            start, goal = TRANSITION_TARGETS[tid]
            for name in names:
                then: list[Action] = (
                    [emits[name][i]]
                    if i < len(ids)
                    else [OpaqueFunction(function=functools.partial(self._remove_handlers, node_name=name))]
                )
                handler = OnStateTransition(matcher=_reaches(name, goal, start), entities=then, handle_once=True)
                self.handlers.setdefault(name, []).append(handler)
                actions.append(RegisterEventHandler(handler))
        for name in names:
            on_error = OnStateTransition(  # launch_ros: an EventHandler with this matcher, the same thing
                matcher=_reaches(name, "errorprocessing"),
                entities=[
                    OpaqueFunction(
                        function=functools.partial(
                            self._remove_handlers, node_name=name, reason="error occured during transitions"
                        )
                    )
                ],
                handle_once=True,
            )
            self.handlers[name].append(on_error)
            context.register_event_handler(on_error)
        actions.extend(emits[name][0] for name in names)
        return actions
