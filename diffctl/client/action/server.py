"""rclpy.action.server: ActionServer and ServerGoalHandle, as rclpy and rcl_action behave in Jazzy.

A goal request asks goal_callback; an accepted goal is stamped, answered, published in the status array and
handed to handle_accepted_callback (by default: execute). execute_callback runs as an executor task and
returns the Result; a goal it leaves active is aborted; an exception aborts it with an empty Result.
get_result answers as soon as the goal is done (at once for an unknown goal: UNKNOWN). Results are kept
result_timeout seconds after the goal ends, then the goal is forgotten.
"""

from __future__ import annotations

import threading
import time
import traceback
from collections.abc import Callable
from enum import Enum
from typing import Any

from diffctl.client.action import goal_states as gs
from diffctl.client.action.deferred import serve
from diffctl.client.exceptions import RCLError
from diffctl.client.waitable import NumberOfEntities

# rcl_action's word for a server whose context was shut down
_SERVER_INVALID = "feedback publisher is invalid, at /project/src/rcl_action/action_server.c:984"


class GoalResponse(Enum):
    REJECT = 1
    ACCEPT = 2


class CancelResponse(Enum):
    REJECT = 1
    ACCEPT = 2


GoalEvent = gs.GoalEvent


def default_handle_accepted_callback(goal_handle: ServerGoalHandle) -> None:
    goal_handle.execute()


def default_goal_callback(goal_request: Any) -> GoalResponse:
    return GoalResponse.ACCEPT


def default_cancel_callback(cancel_request: Any) -> CancelResponse:
    return CancelResponse.REJECT


async def _await_or_execute(callback: Callable[..., Any], *args: Any) -> Any:
    import inspect

    if inspect.iscoroutinefunction(callback):
        return await callback(*args)
    return callback(*args)


def _stamp_ns(stamp: Any) -> int:
    return int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)


class ServerGoalHandle:
    """One accepted goal on the server side."""

    def __init__(self, action_server: ActionServer, goal_info: Any, goal_request: Any) -> None:
        self._action_server = action_server
        self._goal_info = goal_info
        self._goal_request = goal_request
        self._state = gs.ACCEPTED
        self._terminal_s: float | None = None
        self._lock = threading.Lock()
        self._destroyed = False

    def __eq__(self, other: object) -> bool:
        return isinstance(other, ServerGoalHandle) and self.goal_id == other.goal_id

    def __ne__(self, other: object) -> bool:
        return not self.__eq__(other)

    __hash__ = None  # type: ignore[assignment]

    @property
    def request(self) -> Any:
        return self._goal_request

    @property
    def goal_id(self) -> Any:
        return self._goal_info.goal_id

    @property
    def is_active(self) -> bool:
        with self._lock:
            return not self._destroyed and gs.is_active(self._state)

    @property
    def is_cancel_requested(self) -> bool:
        return self.status == gs.CANCELING

    @property
    def status(self) -> int:
        with self._lock:
            return gs.UNKNOWN if self._destroyed else self._state

    def _update_state(self, event: gs.GoalEvent) -> None:
        with self._lock:
            if self._destroyed:
                return
            try:
                self._state = gs.transition(self._state, event)
            except gs.InvalidGoalTransition as e:
                raise RCLError(f"Failed to update goal state: {e}") from None
            done = not gs.is_active(self._state)
            if done:
                self._terminal_s = time.monotonic()
        self._action_server._publish_status()
        if done:
            self._action_server._notify_goal_done()

    def execute(self, execute_callback: Callable[[ServerGoalHandle], Any] | None = None) -> None:
        # A cancel accepted before execution starts leaves the goal CANCELING: the user's callback still
        # runs, to let it finish the cancel.
        if not self.is_cancel_requested:
            self._update_state(gs.GoalEvent.EXECUTE)
        self._action_server.notify_execute(self, execute_callback)

    def publish_feedback(self, feedback: Any) -> None:
        action_type = self._action_server.action_type
        if not isinstance(feedback, action_type.Feedback):
            raise TypeError()
        with self._lock:
            if self._destroyed:
                return
            message = action_type.Impl.FeedbackMessage()
            message.goal_id = self._goal_info.goal_id
            message.feedback = feedback
        pub = self._action_server._feedback_pub
        if not pub._context._ok:
            # rcl_action's refusal, not rcl's: what an execute callback still running after Ctrl-C raises
            raise RCLError(f"Failed to publish feedback with an action server: {_SERVER_INVALID}")
        pub.publish(message)

    def succeed(self) -> None:
        self._update_state(gs.GoalEvent.SUCCEED)

    def abort(self) -> None:
        self._update_state(gs.GoalEvent.ABORT)

    def canceled(self) -> None:
        self._update_state(gs.GoalEvent.CANCELED)

    def destroy(self) -> None:
        with self._lock:
            self._destroyed = True


class ActionServer:
    """rclpy.action.ActionServer."""

    def __init__(
        self,
        node: Any,
        action_type: Any,
        action_name: str,
        execute_callback: Callable[[ServerGoalHandle], Any],
        *,
        callback_group: Any = None,
        goal_callback: Callable[[Any], Any] = default_goal_callback,
        handle_accepted_callback: Callable[[ServerGoalHandle], Any] = default_handle_accepted_callback,
        cancel_callback: Callable[[ServerGoalHandle], Any] = default_cancel_callback,
        goal_service_qos_profile: Any = None,
        result_service_qos_profile: Any = None,
        cancel_service_qos_profile: Any = None,
        feedback_pub_qos_profile: Any = None,
        status_pub_qos_profile: Any = None,
        result_timeout: int = 900,
    ) -> None:
        from action_msgs.msg import GoalStatusArray
        from action_msgs.srv import CancelGoal

        from diffctl.client.qos import QoSProfile, qos_profile_action_status_default, qos_profile_services_default

        self._node = node
        self.action_type = action_type
        self._action_name = action_name
        self.register_callbacks(execute_callback, goal_callback, handle_accepted_callback, cancel_callback)
        self._result_timeout_s = float(result_timeout)
        self._lock = threading.RLock()
        self._goal_handles: dict[bytes, ServerGoalHandle] = {}
        self._results: dict[bytes, Any] = {}
        self._result_waiters: dict[bytes, list[Callable[[Any], None]]] = {}
        self._expire_timer: threading.Timer | None = None
        self._logger = node.get_logger().get_child("action_server")
        group = callback_group if callback_group is not None else node.default_callback_group
        self.callback_group = group
        base = f"{action_name}/_action"
        services = qos_profile_services_default
        self._goal_service = serve(node, action_type.Impl.SendGoalService, f"{base}/send_goal",
                                   self._execute_goal_request, goal_service_qos_profile or services, group)
        self._cancel_service = serve(node, CancelGoal, f"{base}/cancel_goal", self._execute_cancel_request,
                                     cancel_service_qos_profile or services, group)
        self._result_service = serve(node, action_type.Impl.GetResultService, f"{base}/get_result",
                                     self._execute_get_result_request, result_service_qos_profile or services,
                                     group)
        self._feedback_pub = node.create_publisher(
            action_type.Impl.FeedbackMessage, f"{base}/feedback", feedback_pub_qos_profile or QoSProfile(depth=10))
        self._status_pub = node.create_publisher(
            GoalStatusArray, f"{base}/status", status_pub_qos_profile or qos_profile_action_status_default)

    def register_callbacks(self, execute_callback: Any = None, goal_callback: Any = None,
                           handle_accepted_callback: Any = None, cancel_callback: Any = None) -> None:
        if execute_callback is not None:
            self._execute_callback = execute_callback
        if goal_callback is not None:
            self._goal_callback = goal_callback
        if handle_accepted_callback is not None:
            self._handle_accepted_callback = handle_accepted_callback
        if cancel_callback is not None:
            self._cancel_callback = cancel_callback

    register_execute_callback = register_callbacks

    def register_goal_callback(self, goal_callback: Any) -> None:
        self._goal_callback = goal_callback or default_goal_callback

    def register_cancel_callback(self, cancel_callback: Any) -> None:
        self._cancel_callback = cancel_callback or default_cancel_callback

    def register_handle_accepted_callback(self, handle_accepted_callback: Any) -> None:
        self._handle_accepted_callback = handle_accepted_callback or default_handle_accepted_callback

    # --- goals ----------------------------------------------------------------------------------------------
    async def _execute_goal_request(self, goal_request: Any, reply: Callable[[Any], None]) -> None:
        from action_msgs.msg import GoalInfo

        uuid = bytes(goal_request.goal_id.uuid)
        goal_info = GoalInfo()
        goal_info.goal_id = goal_request.goal_id
        accepted = False
        with self._lock:
            known = uuid in self._goal_handles
        if not known:
            response = await _await_or_execute(self._goal_callback, goal_request.goal)
            if not isinstance(response, GoalResponse):
                self._logger.warning("Goal request callback did not return a GoalResponse type. Rejecting goal.")
            else:
                accepted = response == GoalResponse.ACCEPT
        goal_handle = None
        if accepted:
            goal_info.stamp = self._node.get_clock().now().to_msg()
            goal_handle = ServerGoalHandle(self, goal_info, goal_request.goal)
            with self._lock:
                self._goal_handles[uuid] = goal_handle
        response_msg = self.action_type.Impl.SendGoalService.Response()
        response_msg.accepted = accepted
        response_msg.stamp = goal_info.stamp
        reply(response_msg)
        if goal_handle is None:
            return
        self._publish_status()
        await _await_or_execute(self._handle_accepted_callback, goal_handle)

    def notify_execute(self, goal_handle: ServerGoalHandle, execute_callback: Any) -> None:
        callback = execute_callback or self._execute_callback
        executor = self._node.executor
        if executor is None:
            raise RuntimeError("Failed to get node executor, ensure the node has been added to an executor")
        executor.create_task(self._execute_goal, callback, goal_handle)

    async def _execute_goal(self, execute_callback: Any, goal_handle: ServerGoalHandle) -> None:
        uuid = bytes(goal_handle.goal_id.uuid)
        try:
            result = await _await_or_execute(execute_callback, goal_handle)
        except Exception as ex:  # the client still gets an (empty) result, as rclpy does
            result = self.action_type.Result()
            self._logger.error(f"Error raised in execute callback: {ex}")
            traceback.print_exc()
        if goal_handle.is_active:
            self._logger.warning(f"Goal state not set, assuming aborted. Goal ID: {goal_handle.goal_id.uuid}")
            goal_handle.abort()
        response = self.action_type.Impl.GetResultService.Response()
        response.status = goal_handle.status
        response.result = result
        with self._lock:
            self._results[uuid] = response
            waiters = self._result_waiters.pop(uuid, [])
        for reply in waiters:
            reply(response)

    async def _execute_get_result_request(self, request: Any, reply: Callable[[Any], None]) -> None:
        uuid = bytes(request.goal_id.uuid)
        with self._lock:
            if uuid not in self._goal_handles:
                unknown = self.action_type.Impl.GetResultService.Response()
                unknown.status = gs.UNKNOWN
                ready = unknown
            else:
                ready = self._results.get(uuid)
                if ready is None:
                    self._result_waiters.setdefault(uuid, []).append(reply)
        if ready is not None:
            reply(ready)

    async def _execute_cancel_request(self, request: Any, reply: Callable[[Any], None]) -> None:
        from action_msgs.srv import CancelGoal

        with self._lock:
            goals = [(u, _stamp_ns(h._goal_info.stamp), h.status) for u, h in self._goal_handles.items()]
        code, uuids = gs.goals_to_cancel(goals, bytes(request.goal_info.goal_id.uuid),
                                         _stamp_ns(request.goal_info.stamp))
        response = CancelGoal.Response()
        response.return_code = code
        for uuid in uuids:
            with self._lock:
                goal_handle = self._goal_handles.get(uuid)
            if goal_handle is None:
                continue
            answer = await _await_or_execute(self._cancel_callback, goal_handle)
            if answer == CancelResponse.ACCEPT:
                try:
                    goal_handle._update_state(gs.GoalEvent.CANCEL_GOAL)
                except RuntimeError as e:
                    self._logger.warning(f"Failed to cancel goal in cancel callback: {e}")
                    continue
                response.goals_canceling.append(goal_handle._goal_info)
        reply(response)

    # --- status and expiry ----------------------------------------------------------------------------------
    def _publish_status(self) -> None:
        from action_msgs.msg import GoalStatus, GoalStatusArray

        with self._lock:
            handles = list(self._goal_handles.values())
        message = GoalStatusArray()
        message.status_list = [GoalStatus(goal_info=h._goal_info, status=h.status) for h in handles]
        if not self._status_pub._context._ok:
            # rcl_action checks the server (its feedback publisher first) before it builds the array
            raise RCLError(f"Failed get goal status array: {_SERVER_INVALID}")
        self._status_pub.publish(message)

    def _notify_goal_done(self) -> None:
        self._schedule_expiry()

    def _schedule_expiry(self) -> None:
        with self._lock:
            ends = [h._terminal_s for h in self._goal_handles.values() if h._terminal_s is not None]
            if not ends or self._expire_timer is not None:
                return
            delay = max(0.0, min(ends) + self._result_timeout_s - time.monotonic())
            self._expire_timer = threading.Timer(delay, self._expire_goals)
            self._expire_timer.daemon = True
            self._expire_timer.start()

    def _expire_goals(self) -> None:
        now = time.monotonic()
        with self._lock:
            self._expire_timer = None
            expired = [u for u, h in self._goal_handles.items()
                       if h._terminal_s is not None and now - h._terminal_s >= self._result_timeout_s]
            for uuid in expired:
                self._goal_handles.pop(uuid).destroy()
                self._results.pop(uuid, None)
        # As rclpy: forgetting goals publishes no status array (the last one still lists them).
        self._schedule_expiry()

    def get_num_entities(self) -> NumberOfEntities:
        """What rcl_action's server holds: its three services and the goal-expiry timer (a thread here)."""
        return NumberOfEntities(num_timers=1, num_services=3)

    def destroy(self) -> None:
        with self._lock:
            if self._expire_timer is not None:
                self._expire_timer.cancel()
                self._expire_timer = None
            for handle in self._goal_handles.values():
                handle.destroy()
        for service in (self._goal_service, self._cancel_service, self._result_service):
            self._node.destroy_service(service)
        self._node.destroy_publisher(self._feedback_pub)
        self._node.destroy_publisher(self._status_pub)
