"""StateTransition: the event a LifecycleNode emits for each lifecycle_msgs/msg/TransitionEvent of its node."""

from __future__ import annotations

from typing import Any

from diffctl.launch.event import Event


class StateTransition(Event):
    """A lifecycle node went through a transition; `msg` is the TransitionEvent, `action` the LifecycleNode."""

    name = "launch_ros.events.lifecycle.StateTransition"

    def __init__(self, *, action: Any, msg: Any) -> None:
        super().__init__()
        self.__action = action
        self.__msg = msg

    @property
    def action(self) -> Any:
        return self.__action

    @property
    def msg(self) -> Any:
        return self.__msg

    @property
    def timestamp(self) -> int:
        return self.__msg.timestamp

    @property
    def transition(self) -> str:
        return self.__msg.transition.label

    @property
    def start_state(self) -> str:
        return self.__msg.start_state.label

    @property
    def goal_state(self) -> str:
        return self.__msg.goal_state.label
