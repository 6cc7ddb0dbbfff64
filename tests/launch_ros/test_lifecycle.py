"""A managed node driven by LifecycleTransition: the launch's own ROS node asks for each transition when the
previous one reached its goal, and the node's transition events come back as StateTransition events."""

from __future__ import annotations

import sys

import pytest

from diffctl.launch.actions import OpaqueFunction, RegisterEventHandler, Shutdown
from diffctl.launch_ros.actions import LifecycleNode, LifecycleTransition
from diffctl.launch_ros.event_handlers import OnStateTransition
from diffctl.launch_ros.events.lifecycle import ChangeState
from diffctl.launch_ros.events.matchers import matches_node_name

from .conftest import DATA, run


@pytest.mark.slow
def test_lifecycle_transition_walks_a_node_to_active(router: str) -> None:
    from lifecycle_msgs.msg import Transition

    node = LifecycleNode(
        executable=sys.executable,
        arguments=[str(DATA / "lifecycle_node.py")],
        name="lc",
        namespace="ns",
        on_exit=[Shutdown(reason="the managed node ended")],  # a failure ends the launch instead of hanging it
    )
    seen: list[tuple[str, str]] = []

    def record(context) -> None:
        seen.append((context.locals.event.start_state, context.locals.event.goal_state))

    code, _ = run([
        RegisterEventHandler(OnStateTransition(target_lifecycle_node=node, entities=[OpaqueFunction(function=record)])),
        RegisterEventHandler(OnStateTransition(target_lifecycle_node=node, goal_state="active",
                                               entities=[Shutdown(reason="active")])),
        node,
        LifecycleTransition(lifecycle_node_names=["/ns/lc"], transition_ids=[Transition.TRANSITION_CONFIGURE, "3"]),
    ])  # fmt: skip
    assert code == 0
    assert seen == [("unconfigured", "configuring"), ("configuring", "inactive"), ("inactive", "activating"),
                    ("activating", "active")]  # fmt: skip


def test_change_state_takes_lifecycle_msgs_transition_ids_only() -> None:
    from lifecycle_msgs.msg import State, Transition

    # the transitions one asks for (ids below 10; the others are the outcomes of callbacks)
    transitions = {v: k for k, v in vars(Transition).items() if k.startswith("TRANSITION_") and v < 10}
    assert dict(ChangeState.valid_transitions) == transitions
    states = {v: k for k, v in vars(State).items() if k.startswith(("PRIMARY_STATE_", "TRANSITION_STATE_"))}
    assert dict(ChangeState.valid_states) == states
    with pytest.raises(ValueError, match="given transition_id of '42'"):
        ChangeState(lifecycle_node_matcher=matches_node_name("x"), transition_id=42)
