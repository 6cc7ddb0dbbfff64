"""tf2_ros.buffer_client.BufferClient: lookups answered by a tf2 BufferServer over the tf2_msgs
LookupTransform action (the server's namespace is the action's name), as tf2_ros's Python client.

Calls block until the server answers: another thread must spin the node (as with tf2_ros's). A lookup waits at
most its timeout plus `timeout_padding` for the goal to be accepted and again for its result.
"""

from __future__ import annotations

import threading
from typing import Any

from diffctl.tf2 import exceptions as tf2
from diffctl.tf2.ros_io import BufferInterface


def _default_padding() -> Any:
    from rclpy.duration import Duration

    return Duration(seconds=2.0)


class BufferClient(BufferInterface):
    def __init__(self, node: Any, ns: str, check_frequency: float = 10.0, timeout_padding: Any = None) -> None:
        from rclpy.action import ActionClient
        from tf2_msgs.action import LookupTransform

        super().__init__()
        self.node = node
        self.action_client = ActionClient(node, LookupTransform, action_name=ns)
        self.check_frequency = check_frequency
        self.timeout_padding = _default_padding() if timeout_padding is None else timeout_padding
        self._goal_type = LookupTransform.Goal

    def lookup_transform(self, target_frame: str, source_frame: str, time: Any, timeout: Any = None) -> Any:
        goal = self._goal_type(target_frame=target_frame, source_frame=source_frame,
                               source_time=_time(time).to_msg(), timeout=_timeout(timeout).to_msg(), advanced=False)
        return self._process_goal(goal)

    def lookup_transform_full(self, target_frame: str, target_time: Any, source_frame: str, source_time: Any,
                              fixed_frame: str, timeout: Any = None) -> Any:
        goal = self._goal_type(target_frame=target_frame, source_frame=source_frame,
                               source_time=_time(source_time).to_msg(), timeout=_timeout(timeout).to_msg(),
                               target_time=_time(target_time).to_msg(), fixed_frame=fixed_frame, advanced=True)
        return self._process_goal(goal)

    def can_transform(self, target_frame: str, source_frame: str, time: Any, timeout: Any = None) -> bool:
        try:
            self.lookup_transform(target_frame, source_frame, time, timeout)
        except tf2.TransformException:
            return False
        return True

    def can_transform_full(self, target_frame: str, target_time: Any, source_frame: str, source_time: Any,
                           fixed_frame: str, timeout: Any = None) -> bool:
        try:
            self.lookup_transform_full(target_frame, target_time, source_frame, source_time, fixed_frame, timeout)
        except tf2.TransformException:
            return False
        return True

    def _process_goal(self, goal: Any) -> Any:
        from rclpy.duration import Duration

        if not self.action_client.server_is_ready():
            raise tf2.TimeoutException("The BufferServer is not ready.")
        wait_s = (Duration.from_msg(goal.timeout).nanoseconds + self.timeout_padding.nanoseconds) / 1e9
        send = self.action_client.send_goal_async(goal)
        if not _wait(send, wait_s):
            raise tf2.TimeoutException(
                "The LookupTransform goal sent to the BufferServer did not come back in the specified time. "
                "Something is likely wrong with the server.")
        handle = send.result()
        if not handle.accepted:
            raise tf2.TimeoutException(
                "The LookupTransform goal sent to the BufferServer did not come back with accepted status. "
                "Something is likely wrong with the server.")
        result = handle.get_result_async()
        if not _wait(result, wait_s):
            raise tf2.TimeoutException("The BufferServer did not send the LookupTransform result in time.")
        return _transform_or_raise(result.result().result)

    def destroy(self) -> None:
        self.action_client.destroy()


_ERRORS = {1: tf2.LookupException, 2: tf2.ConnectivityException, 3: tf2.ExtrapolationException,
           4: tf2.InvalidArgumentException, 5: tf2.TimeoutException}  # tf2_msgs/TF2Error codes


def _transform_or_raise(result: Any) -> Any:
    if result is None or result.error is None:
        raise tf2.TransformException("The BufferServer returned None for result or result.error!  "
                                     "Something is likely wrong with the server.")
    code = int(result.error.error)
    if code != 0:
        raise _ERRORS.get(code, tf2.TransformException)(result.error.error_string)
    return result.transform


def _wait(future: Any, timeout_s: float) -> bool:
    done = threading.Event()
    future.add_done_callback(lambda _f: done.set())
    return future.done() or done.wait(timeout_s)


def _time(t: Any) -> Any:
    from builtin_interfaces.msg import Time as TimeMsg
    from rclpy.time import Time

    if isinstance(t, TimeMsg):
        return Time.from_msg(t)
    if isinstance(t, Time):
        return t
    raise TypeError("Must pass a rclpy.time.Time object.")


def _timeout(d: Any) -> Any:
    from rclpy.duration import Duration

    return Duration() if d is None else d
