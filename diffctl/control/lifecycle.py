"""Managed-node lifecycle of controllers and hardware: states, ids and the non-real-time transitions.

States and transitions follow ROS 2 managed nodes as ros2_control uses them: load → unconfigured,
configure → inactive (from inactive: cleanup first), activate/deactivate only through a switch,
cleanup inactive → unconfigured, unload = cleanup if needed, then shutdown → finalized.
A hook that raises makes the transition fail; the controller stays where it was and the message says why.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field

from diffctl.control.controller_interface import ControllerInterface
from diffctl.errors import RuntimeFailure


class State(enum.StrEnum):
    UNKNOWN = "unknown"
    UNCONFIGURED = "unconfigured"
    INACTIVE = "inactive"
    ACTIVE = "active"
    FINALIZED = "finalized"

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


@dataclass(eq=False)
class ManagedController:
    """A loaded controller as the manager tracks it."""

    name: str
    type_name: str
    instance: ControllerInterface
    state: State = State.UNCONFIGURED
    update_rate: int = 0  # effective Hz; 0 = every manager cycle
    claimed: list[str] = field(default_factory=list)
    required_command: list[str] = field(default_factory=list)
    required_state: list[str] = field(default_factory=list)
    last_update_ns: int | None = None
    update_count: int = 0
    last_error: str = ""
    fallback_controllers: tuple[str, ...] = ()

    def _call(self, what: str, hook) -> None:
        try:
            hook()
        except Exception as e:
            raise TransitionError(f"controller '{self.name}': {what} failed: {hook_message(e)}") from e

    def configure(self) -> None:
        if self.state is State.INACTIVE:
            self.cleanup()
        if self.state is not State.UNCONFIGURED:
            raise TransitionError(
                f"controller '{self.name}' can not be configured from '{self.state.value}' state"
                + (" (deactivate it first)" if self.state is State.ACTIVE else "")
            )
        self._call("on_configure", self.instance.on_configure)
        self.state = State.INACTIVE

    def cleanup(self) -> None:
        if self.state is not State.INACTIVE:
            raise TransitionError(
                f"controller '{self.name}' can not be cleaned up from '{self.state.value}' state "
                "(only an inactive controller can)"
            )
        self._call("on_cleanup", self.instance.on_cleanup)
        self.state = State.UNCONFIGURED

    def shutdown(self) -> None:
        if self.state is State.ACTIVE:
            raise TransitionError(f"controller '{self.name}' is still active; deactivate it before unloading")
        if self.state is State.INACTIVE:
            self.cleanup()
        if self.state is not State.FINALIZED:
            try:
                self.instance.on_shutdown()
            finally:
                self.state = State.FINALIZED
