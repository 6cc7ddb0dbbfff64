"""rclpy.action.client: ActionClient and ClientGoalHandle, as rclpy behaves in Jazzy.

send_goal_async gives a Future of a ClientGoalHandle (accepted or not); feedback callbacks get the whole
FeedbackMessage; get_result_async gives the GetResult response (.status, .result); cancel_goal_async the
CancelGoal response. Goal handles follow the server's status topic.
"""

from __future__ import annotations

import threading
import time
import uuid as uuidlib
import weakref
from collections.abc import Callable
from typing import Any

from diffctl.client.exceptions import RCLError
from diffctl.client.waitable import NumberOfEntities

WAIT_FOR_SERVER_POLL_S = 0.25  # rclpy's wait_for_server sleeps this long between looks


class ClientGoalHandle:
    """A goal sent by an ActionClient."""

    def __init__(self, action_client: ActionClient, goal_id: Any, goal_response: Any) -> None:
        from action_msgs.msg import GoalStatus

        self._action_client = action_client
        self._goal_id = goal_id
        self._goal_response = goal_response
        self._status = GoalStatus.STATUS_UNKNOWN

    def __eq__(self, other: object) -> bool:
        return isinstance(other, ClientGoalHandle) and bytes(self._goal_id.uuid) == bytes(other._goal_id.uuid)

    def __ne__(self, other: object) -> bool:
        return not self.__eq__(other)

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return f"ClientGoalHandle <id={self.goal_id.uuid}, accepted={self.accepted}, status={self.status}>"

    @property
    def goal_id(self) -> Any:
        return self._goal_id

    @property
    def stamp(self) -> Any:
        return self._goal_response.stamp

    @property
    def accepted(self) -> bool:
        return self._goal_response.accepted

    @property
    def status(self) -> int:
        return self._status

    def cancel_goal(self) -> Any:
        return self._action_client._cancel_goal(self)

    def cancel_goal_async(self) -> Any:
        return self._action_client._cancel_goal_async(self)

    def get_result(self) -> Any:
        return self._action_client._get_result(self)

    def get_result_async(self) -> Any:
        return self._action_client._get_result_async(self)


class ActionClient:
    """rclpy.action.ActionClient."""

    def __init__(
        self,
        node: Any,
        action_type: Any,
        action_name: str,
        *,
        callback_group: Any = None,
        goal_service_qos_profile: Any = None,
        result_service_qos_profile: Any = None,
        cancel_service_qos_profile: Any = None,
        feedback_sub_qos_profile: Any = None,
        status_sub_qos_profile: Any = None,
    ) -> None:
        from action_msgs.msg import GoalStatusArray
        from action_msgs.srv import CancelGoal

        from diffctl.client.qos import QoSProfile, qos_profile_action_status_default, qos_profile_services_default

        self._node = node
        self._action_type = action_type
        self._action_name = action_name
        group = callback_group if callback_group is not None else node.default_callback_group
        self.callback_group = group
        services = qos_profile_services_default
        base = f"{action_name}/_action"
        self._goal_client = node.create_client(action_type.Impl.SendGoalService, f"{base}/send_goal",
                                               qos_profile=goal_service_qos_profile or services, callback_group=group)
        self._cancel_client = node.create_client(CancelGoal, f"{base}/cancel_goal",
                                                 qos_profile=cancel_service_qos_profile or services,
                                                 callback_group=group)
        self._result_client = node.create_client(action_type.Impl.GetResultService, f"{base}/get_result",
                                                 qos_profile=result_service_qos_profile or services,
                                                 callback_group=group)
        self._feedback_sub = node.create_subscription(
            action_type.Impl.FeedbackMessage, f"{base}/feedback", self._on_feedback,
            feedback_sub_qos_profile or QoSProfile(depth=10), callback_group=group)
        self._status_sub = node.create_subscription(
            GoalStatusArray, f"{base}/status", self._on_status,
            status_sub_qos_profile or qos_profile_action_status_default, callback_group=group)
        self._lock = threading.Lock()
        self._feedback_callbacks: dict[bytes, Callable[[Any], None]] = {}
        self._goal_handles: dict[bytes, weakref.ref[ClientGoalHandle]] = {}

    # --- sending goals --------------------------------------------------------------------------------------
    def send_goal_async(self, goal: Any, feedback_callback: Callable[[Any], None] | None = None,
                        goal_uuid: Any = None) -> Any:
        from unique_identifier_msgs.msg import UUID

        from diffctl.client.task import Future

        if not isinstance(goal, self._action_type.Goal):
            raise TypeError()
        if goal_uuid is None:
            goal_uuid = UUID(uuid=list(uuidlib.uuid4().bytes))
        request = self._action_type.Impl.SendGoalService.Request()
        request.goal_id = goal_uuid
        request.goal = goal
        key = bytes(goal_uuid.uuid)
        if feedback_callback is not None:
            with self._lock:
                self._feedback_callbacks[key] = feedback_callback
        outer = Future()
        inner = self._goal_client.call_async(request)

        def on_response(done: Any) -> None:
            if done.cancelled():
                outer.cancel()
                return
            error = done.exception()
            if error is not None:
                outer.set_exception(error)
                return
            response = done.result()
            handle = ClientGoalHandle(self, goal_uuid, response)
            with self._lock:
                if handle.accepted:
                    self._goal_handles[key] = weakref.ref(handle)
                else:
                    self._feedback_callbacks.pop(key, None)
            outer.set_result(handle)

        inner.add_done_callback(on_response)
        outer.add_done_callback(lambda f: inner.cancel() if f.cancelled() and not inner.done() else None)
        return outer

    def send_goal(self, goal: Any, **kwargs: Any) -> Any:
        """Send a goal and block until its result (another thread must be spinning the node)."""
        if not isinstance(goal, self._action_type.Goal):
            raise TypeError()
        handle = self._wait(self.send_goal_async(goal, **kwargs))
        if handle is None or not handle.accepted:
            return None
        return self._get_result(handle)

    # --- results and cancels --------------------------------------------------------------------------------
    def _get_result_async(self, goal_handle: ClientGoalHandle) -> Any:
        if not isinstance(goal_handle, ClientGoalHandle):
            raise TypeError(f"Expected type ClientGoalHandle but received {type(goal_handle)}")
        request = self._action_type.Impl.GetResultService.Request()
        request.goal_id = goal_handle.goal_id
        future = self._result_client.call_async(request)
        key = bytes(goal_handle.goal_id.uuid)

        def on_result(done: Any) -> None:
            with self._lock:
                self._feedback_callbacks.pop(key, None)
            if not done.cancelled() and done.exception() is None and done.result() is not None:
                goal_handle._status = done.result().status

        future.add_done_callback(on_result)
        return future

    def _get_result(self, goal_handle: ClientGoalHandle) -> Any:
        return self._wait(self._get_result_async(goal_handle))

    def _cancel_goal_async(self, goal_handle: ClientGoalHandle) -> Any:
        from action_msgs.srv import CancelGoal

        if not isinstance(goal_handle, ClientGoalHandle):
            raise TypeError(f"Expected type ClientGoalHandle but received {type(goal_handle)}")
        request = CancelGoal.Request()
        request.goal_info.goal_id = goal_handle.goal_id
        return self._cancel_client.call_async(request)

    def _cancel_goal(self, goal_handle: ClientGoalHandle) -> Any:
        return self._wait(self._cancel_goal_async(goal_handle))

    @staticmethod
    def _wait(future: Any) -> Any:
        event = threading.Event()
        future.add_done_callback(lambda _f: event.set())
        event.wait()
        error = future.exception()
        if error is not None:
            raise error
        return future.result()

    # --- topics ---------------------------------------------------------------------------------------------
    def _on_feedback(self, message: Any) -> None:
        with self._lock:
            callback = self._feedback_callbacks.get(bytes(message.goal_id.uuid))
        if callback is not None:
            callback(message)

    def _on_status(self, message: Any) -> None:
        for status in message.status_list:
            key = bytes(status.goal_info.goal_id.uuid)
            with self._lock:
                ref = self._goal_handles.get(key)
            handle = ref() if ref is not None else None
            if handle is None:
                with self._lock:
                    self._goal_handles.pop(key, None)
                continue
            handle._status = status.status

    # --- the server -----------------------------------------------------------------------------------------
    def server_is_ready(self) -> bool:
        if not self._node.context.ok():
            raise RCLError("Failed to check if action server is available: rcl node's context is invalid, "
                           "at /project/src/rcl/node.c:404")
        return all(c.service_is_ready() for c in (self._goal_client, self._cancel_client, self._result_client))

    def wait_for_server(self, timeout_sec: float | None = None) -> bool:
        remaining = float("inf") if timeout_sec is None else timeout_sec
        while self._node.context.ok() and not self.server_is_ready() and remaining > 0.0:
            time.sleep(WAIT_FOR_SERVER_POLL_S)
            remaining -= WAIT_FOR_SERVER_POLL_S
        return self.server_is_ready()

    def get_num_entities(self) -> NumberOfEntities:
        """What rcl_action's client holds: the feedback and status subscriptions and the three clients."""
        return NumberOfEntities(num_subs=2, num_clients=3)

    def destroy(self) -> None:
        for client in (self._goal_client, self._cancel_client, self._result_client):
            self._node.destroy_client(client)
        for sub in (self._feedback_sub, self._status_sub):
            self._node.destroy_subscription(sub)
