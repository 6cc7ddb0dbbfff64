"""The action goal state machine of rcl_action (goal_state_machine.c): states are GoalStatus values,
events move a goal between them; anything else is refused with rcl_action's words."""

from __future__ import annotations

import enum

UNKNOWN, ACCEPTED, EXECUTING, CANCELING, SUCCEEDED, CANCELED, ABORTED = range(7)
STATE_NAMES = ("UNKNOWN", "ACCEPTED", "EXECUTING", "CANCELING", "SUCCEEDED", "CANCELED", "ABORTED")


class GoalEvent(enum.IntEnum):
    EXECUTE = 0
    CANCEL_GOAL = 1
    SUCCEED = 2
    ABORT = 3
    CANCELED = 4


_TRANSITIONS: dict[tuple[int, GoalEvent], int] = {
    (ACCEPTED, GoalEvent.EXECUTE): EXECUTING,
    (ACCEPTED, GoalEvent.CANCEL_GOAL): CANCELING,
    (EXECUTING, GoalEvent.CANCEL_GOAL): CANCELING,
    (EXECUTING, GoalEvent.SUCCEED): SUCCEEDED,
    (EXECUTING, GoalEvent.ABORT): ABORTED,
    (CANCELING, GoalEvent.SUCCEED): SUCCEEDED,
    (CANCELING, GoalEvent.ABORT): ABORTED,
    (CANCELING, GoalEvent.CANCELED): CANCELED,
}


class InvalidGoalTransition(Exception):
    """An event the goal's state does not allow (rcl_action's RCL_RET_ACTION_GOAL_EVENT_INVALID)."""


def transition(state: int, event: GoalEvent) -> int:
    new = _TRANSITIONS.get((state, GoalEvent(event)))
    if new is None:
        raise InvalidGoalTransition(
            f"goal_handle attempted invalid transition from state {STATE_NAMES[state]} "
            f"with event {GoalEvent(event).name}"
        )
    return new


def is_active(state: int) -> bool:
    return state in (ACCEPTED, EXECUTING, CANCELING)


def is_cancelable(state: int) -> bool:
    return state in (ACCEPTED, EXECUTING)


def goals_to_cancel(
    goals: list[tuple[bytes, int, int]], request_uuid: bytes, request_stamp_ns: int
) -> tuple[int, list[bytes]]:
    """rcl_action_process_cancel_request over (uuid, accept stamp ns, state) in acceptance order:
    (return code, uuids to cancel). Codes: 0 NONE, 2 UNKNOWN_GOAL_ID, 3 GOAL_TERMINATED."""
    zero_uuid = not any(request_uuid)
    if not zero_uuid and request_stamp_ns == 0:
        for uuid, _, state in goals:
            if uuid == request_uuid:
                return (0, [uuid]) if is_cancelable(state) else (3, [])
        return 2, []
    until = (1 << 63) - 1 if zero_uuid and request_stamp_ns == 0 else request_stamp_ns
    return 0, [
        uuid for uuid, stamp, state in goals if is_cancelable(state) and (stamp <= until or uuid == request_uuid)
    ]
