"""realtime_tools' RealtimeServerGoalHandle for controllers with an action server (trajectory, gripper).

The control loop decides a goal's outcome and its feedback, but must not wait on the action server, so it only
records them (`set_feedback`, `set_succeeded`, `set_aborted`, `set_canceled`: cheap stores); a timer on the
controller's executor calls `run_non_realtime()` at the controller's action_monitor_rate, which publishes the
latest feedback and carries an outcome out: the goal's state changes (succeeded / aborted / canceled, a cancel
only once the server has accepted the cancel request) and the execute callback — which awaits `result` —
returns the result to the client.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from diffctl.client.task import Future

SUCCEEDED, ABORTED, CANCELED = "succeeded", "aborted", "canceled"


class RealtimeGoal:
    def __init__(self, goal_handle: Any, make_feedback: Callable[[Any], Any] | None = None) -> None:
        self.goal_handle = goal_handle
        self.result: Future = Future()
        self._outcome: tuple[str, Any] | None = None
        self._feedback: Any = None  # what the loop last reported; make_feedback turns it into the message
        self._make_feedback = make_feedback

    # --- control loop side -------------------------------------------------------------------------------
    def set_feedback(self, snapshot: Any) -> None:
        self._feedback = snapshot

    def _set(self, kind: str, result: Any) -> None:
        if self._outcome is None:  # the first decision stands
            self._outcome = (kind, result)

    def set_succeeded(self, result: Any) -> None:
        self._set(SUCCEEDED, result)

    def set_aborted(self, result: Any) -> None:
        self._set(ABORTED, result)

    def set_canceled(self, result: Any) -> None:
        self._set(CANCELED, result)

    @property
    def decided(self) -> bool:
        return self._outcome is not None

    # --- executor side --------------------------------------------------------------------------------------
    def run_non_realtime(self) -> None:
        gh = self.goal_handle
        snapshot, self._feedback = self._feedback, None
        if snapshot is not None and gh.is_active and self._make_feedback is not None:
            gh.publish_feedback(self._make_feedback(snapshot))
        outcome = self._outcome
        if outcome is None or self.result.done():
            return
        kind, result = outcome
        if gh.is_active:
            if kind == CANCELED:
                if not gh.is_cancel_requested:
                    return  # the server takes the cancel request after the callback returned: next tick
                gh.canceled()
            elif kind == SUCCEEDED:
                gh.succeed()
            else:
                gh.abort()
        self.result.set_result(result)

    async def execute(self, goal_handle: Any) -> Any:
        """The action server's execute callback: the result, once the control loop decided it."""
        return await self.result
