"""ChangeState: the event that asks lifecycle nodes (those its matcher accepts) for a transition."""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable
from typing import Any, ClassVar

from diffctl.launch.event import Event

from .lifecycle_msgs_ids import STATES, TRANSITIONS


class ChangeState(Event):
    """Ask the lifecycle nodes `lifecycle_node_matcher` accepts to make transition `transition_id`
    (a lifecycle_msgs/msg/Transition id; ValueError for another number)."""

    name = "launch_ros.events.lifecycle.ChangeState"

    valid_transitions: ClassVar[OrderedDict[int, str]] = OrderedDict(TRANSITIONS)
    valid_states: ClassVar[OrderedDict[int, str]] = OrderedDict(STATES)

    def __init__(self, *, lifecycle_node_matcher: Callable[[Any], bool], transition_id: int) -> None:
        super().__init__()
        self.__lifecycle_node_matcher = lifecycle_node_matcher
        self.__transition_id = transition_id
        if transition_id not in self.valid_transitions:
            expected = ", ".join(f"{label}: {tid}" for tid, label in self.valid_transitions.items())
            raise ValueError(f"given transition_id of '{transition_id}', expected one of {{{expected}}}")

    @property
    def lifecycle_node_matcher(self) -> Callable[[Any], bool]:
        return self.__lifecycle_node_matcher

    @property
    def transition_id(self) -> int:
        return self.__transition_id
