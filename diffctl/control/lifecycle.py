"""Managed-node lifecycle of controllers and hardware: states, ids and the non-real-time transitions.

States and transitions follow ROS 2 managed nodes as ros2_control uses them: load → unconfigured,
configure → inactive (from inactive: cleanup first), activate/deactivate only through a switch,
cleanup inactive → unconfigured, unload = cleanup if needed, then shutdown → finalized.
A hook that raises makes the transition fail; the controller stays where it was and the message says why.
"""

from __future__ import annotations

import enum
from collections.abc import Callable
from typing import Any

from diffctl.control.controller_interface import CallbackReturn, ControllerInterface
from diffctl.errors import RuntimeFailure


class State(enum.StrEnum):
    UNKNOWN = "unknown"
    UNCONFIGURED = "unconfigured"
    INACTIVE = "inactive"
    ACTIVE = "active"
    FINALIZED = "finalized"

    @property
    def label(self) -> str:
        return self.value

    def __repr__(self) -> str:
        return f"State({self.value})"

    @property
    def id(self) -> int:
        """lifecycle_msgs/msg/State id."""
        return _IDS[self]

    @classmethod
    def from_id(cls, state_id: int) -> State:
        for s, i in _IDS.items():
            if i == state_id:
                return s
        raise ValueError(state_id)

    @classmethod
    def parse(cls, label: str) -> State:
        try:
            return cls(label.strip().lower())
        except ValueError:
            raise TransitionError(
                f"unknown state {label!r}; valid: unconfigured, inactive, active, finalized"
            ) from None


_IDS = {State.UNKNOWN: 0, State.UNCONFIGURED: 1, State.INACTIVE: 2, State.ACTIVE: 3, State.FINALIZED: 4}


class TransitionError(RuntimeFailure):
    """A lifecycle transition that is not allowed from the current state, or whose hook failed."""


def hook_message(exc: BaseException) -> str:
    text = str(exc) or type(exc).__name__
    return text if type(exc).__module__.startswith("diffctl") else f"{type(exc).__name__}: {text}"


class ManagedController:
    """A loaded controller as the manager tracks it; its lifecycle state is the controller's own."""

    def __init__(self, name: str, type_name: str, instance: ControllerInterface, state: State = State.UNCONFIGURED,
                 update_rate: int = 0, fallback_controllers: tuple[str, ...] = ()) -> None:
        self.name = name
        self.type_name = type_name
        self.instance = instance
        self.state = state
        self.update_rate = update_rate  # effective Hz
        self.fallback_controllers = fallback_controllers
        self.claimed: list[str] = []
        self.required_command: list[str] = []
        self.required_state: list[str] = []
        self.last_update_ns: int | None = None
        self.update_count = 0
        self.last_error = ""

    @property
    def state(self) -> State:
        return self.instance._state or State.UNKNOWN

    @state.setter
    def state(self, value: State) -> None:
        self.instance._state = value

    def call(self, what: str, hook: Callable[[State], Any]) -> None:
        """Run a transition hook with the state it leaves; raise TransitionError when it fails."""
        try:
            result = hook(self.state)
        except Exception as e:
            raise TransitionError(f"controller '{self.name}': {what} failed: {hook_message(e)}") from e
        if result is not None and result is not CallbackReturn.SUCCESS:
            raise TransitionError(f"controller '{self.name}': {what} returned {result.name}")

    def configure(self) -> None:
        if self.state is State.INACTIVE:
            self.cleanup()
        if self.state is not State.UNCONFIGURED:
            raise TransitionError(
                f"controller '{self.name}' can not be configured from '{self.state.value}' state"
                + (" (deactivate it first)" if self.state is State.ACTIVE else "")
            )
        self.call("on_configure", self.instance.on_configure)
        self.state = State.INACTIVE

    def cleanup(self) -> None:
        if self.state is not State.INACTIVE:
            raise TransitionError(
                f"controller '{self.name}' can not be cleaned up from '{self.state.value}' state "
                "(only an inactive controller can)"
            )
        self.call("on_cleanup", self.instance.on_cleanup)
        self.state = State.UNCONFIGURED

    def shutdown(self) -> None:
        if self.state is State.ACTIVE:
            raise TransitionError(f"controller '{self.name}' is still active; deactivate it before unloading")
        if self.state is State.INACTIVE:
            self.cleanup()
        if self.state is not State.FINALIZED:
            try:
                self.call("on_shutdown", self.instance.on_shutdown)
            finally:
                self.state = State.FINALIZED
                self.instance.release_interfaces()
