"""rcl_lifecycle's default state machine as Jazzy's rcl (9.2) registers it: primary and transition states,
transitions with their ids and labels in registration order (the order of ~/get_transition_graph and of
~/get_available_transitions). A callback's return value triggers the transition labelled
`transition_success`/`_failure`/`_error` leaving the transition state."""

from __future__ import annotations

from dataclasses import dataclass

# lifecycle_msgs/msg/State
UNKNOWN, UNCONFIGURED, INACTIVE, ACTIVE, FINALIZED = 0, 1, 2, 3, 4
CONFIGURING, CLEANINGUP, SHUTTINGDOWN, ACTIVATING, DEACTIVATING, ERRORPROCESSING = 10, 11, 12, 13, 14, 15

STATES: dict[int, str] = {
    UNKNOWN: "unknown",
    UNCONFIGURED: "unconfigured",
    INACTIVE: "inactive",
    ACTIVE: "active",
    FINALIZED: "finalized",
    CONFIGURING: "configuring",
    CLEANINGUP: "cleaningup",
    SHUTTINGDOWN: "shuttingdown",
    ACTIVATING: "activating",
    DEACTIVATING: "deactivating",
    ERRORPROCESSING: "errorprocessing",
}

SUCCESS_LABEL, FAILURE_LABEL, ERROR_LABEL = "transition_success", "transition_failure", "transition_error"


@dataclass(frozen=True)
class Transition:
    id: int
    label: str
    start: int
    goal: int


def _results(base: int, start: int, success: int, failure: int, error: int) -> list[Transition]:
    return [
        Transition(base, SUCCESS_LABEL, start, success),
        Transition(base + 1, FAILURE_LABEL, start, failure),
        Transition(base + 2, ERROR_LABEL, start, error),
    ]


TRANSITIONS: tuple[Transition, ...] = (
    Transition(1, "configure", UNCONFIGURED, CONFIGURING),
    *_results(10, CONFIGURING, INACTIVE, UNCONFIGURED, ERRORPROCESSING),
    Transition(2, "cleanup", INACTIVE, CLEANINGUP),
    *_results(20, CLEANINGUP, UNCONFIGURED, INACTIVE, ERRORPROCESSING),
    Transition(3, "activate", INACTIVE, ACTIVATING),
    *_results(30, ACTIVATING, ACTIVE, INACTIVE, ERRORPROCESSING),
    Transition(4, "deactivate", ACTIVE, DEACTIVATING),
    *_results(40, DEACTIVATING, INACTIVE, ACTIVE, ERRORPROCESSING),
    Transition(5, "shutdown", UNCONFIGURED, SHUTTINGDOWN),
    Transition(6, "shutdown", INACTIVE, SHUTTINGDOWN),
    Transition(7, "shutdown", ACTIVE, SHUTTINGDOWN),
    *_results(50, SHUTTINGDOWN, FINALIZED, FINALIZED, ERRORPROCESSING),
    *_results(60, ERRORPROCESSING, UNCONFIGURED, FINALIZED, FINALIZED),
)

# The callback rclpy's LifecycleNodeMixin runs on entering each transition state.
CALLBACK_OF_STATE = {
    CONFIGURING: "on_configure",
    CLEANINGUP: "on_cleanup",
    SHUTTINGDOWN: "on_shutdown",
    ACTIVATING: "on_activate",
    DEACTIVATING: "on_deactivate",
    ERRORPROCESSING: "on_error",
}


class TransitionNotRegistered(Exception):
    """No transition with that id or label leaves the current state; the text is rcl_lifecycle's warning."""


def valid_transitions(state: int) -> list[Transition]:
    return [t for t in TRANSITIONS if t.start == state]


def by_id(state: int, transition_id: int) -> Transition:
    for t in valid_transitions(state):
        if t.id == transition_id:
            return t
    raise TransitionNotRegistered(f"No transition matching {transition_id} found for current state {STATES[state]}")


def by_label(state: int, label: str) -> Transition:
    for t in valid_transitions(state):
        if t.label == label:
            return t
    raise TransitionNotRegistered(f"No transition matching {label} found for current state {STATES[state]}")
