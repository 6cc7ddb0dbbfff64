"""tf2_ros over the rclpy-compatible client: the message-level BufferCore (tf2_py's), Buffer with its waits
and `tf2_frames` service, TransformListener on /tf and /tf_static, and the two broadcasters.

Written against rclpy's public API (the overlay's `rclpy`), as tf2_ros is; the math is `buffer_core`'s.
"""

from __future__ import annotations

import sys
import threading
import time as _time
from collections.abc import Callable, Iterable
from copy import deepcopy
from typing import Any, ClassVar

from diffctl.tf2 import buffer_core
from diffctl.tf2.exceptions import TransformException

TF_TOPIC = "/tf"
TF_STATIC_TOPIC = "/tf_static"
WAIT_POLL_S = 0.02  # tf2_ros's can_transform polls at this period while it waits


def time_ns(t: Any) -> int:
    """Nanoseconds of an rclpy Time, a builtin_interfaces Time message, or an int of nanoseconds."""
    if isinstance(t, int):
        return t
    ns = getattr(t, "nanoseconds", None)
    if ns is not None:
        return int(ns)
    if hasattr(t, "sec") and hasattr(t, "nanosec"):
        return int(t.sec) * 1_000_000_000 + int(t.nanosec)
    raise TypeError(f"expected a rclpy.time.Time or a builtin_interfaces/msg/Time, got {type(t).__name__}")


def duration_ns(d: Any) -> int:
    if d is None:
        return 0
    if isinstance(d, (int, float)):
        return int(d * 1e9)
    ns = getattr(d, "nanoseconds", None)
    if ns is not None:
        return int(ns)
    return int(d.sec) * 1_000_000_000 + int(d.nanosec)


def _log_refusal(reason: str | None) -> None:
    # tf2 reports through console_bridge on stderr; the refused transform is dropped.
    if reason:
        print(f"Error:   {reason}", file=sys.stderr, flush=True)


def _stamped(stamp_ns: int, target: str, source: str, t: tuple, q: tuple) -> Any:
    from builtin_interfaces.msg import Time as TimeMsg
    from geometry_msgs.msg import TransformStamped

    msg = TransformStamped()
    msg.header.stamp = TimeMsg(sec=stamp_ns // 1_000_000_000, nanosec=stamp_ns % 1_000_000_000)
    msg.header.frame_id = target
    msg.child_frame_id = source
    tr, rot = msg.transform.translation, msg.transform.rotation
    tr.x, tr.y, tr.z = (float(v) for v in t)
    rot.x, rot.y, rot.z, rot.w = (float(v) for v in q)
    return msg


class BufferCore:
    """tf2_py.BufferCore: TransformStamped messages in and out."""

    def __init__(self, cache_time: Any = None) -> None:
        ns = duration_ns(cache_time) if cache_time is not None else buffer_core.DEFAULT_CACHE_TIME_NS
        self._core = buffer_core.BufferCore(ns)

    def _set(self, transform: Any, authority: str, is_static: bool) -> None:
        tr, rot = transform.transform.translation, transform.transform.rotation
        _log_refusal(
            self._core.set_transform(
                transform.header.frame_id,
                transform.child_frame_id,
                time_ns(transform.header.stamp),
                (tr.x, tr.y, tr.z),
                (rot.x, rot.y, rot.z, rot.w),
                authority,
                is_static,
            )
        )

    def set_transform(self, transform: Any, authority: str) -> None:
        self._set(transform, authority, False)

    def set_transform_static(self, transform: Any, authority: str) -> None:
        self._set(transform, authority, True)

    def lookup_transform_core(self, target_frame: str, source_frame: str, time: Any) -> Any:
        stamp, t, q = self._core.lookup_transform(target_frame, source_frame, time_ns(time))
        return _stamped(stamp, target_frame, source_frame, t, q)

    def lookup_transform_full_core(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str
    ) -> Any:
        stamp, t, q = self._core.lookup_transform_full(
            target_frame, time_ns(target_time), source_frame, time_ns(source_time), fixed_frame
        )
        return _stamped(stamp, target_frame, source_frame, t, q)

    def can_transform_core(self, target_frame: str, source_frame: str, time: Any) -> tuple[bool, str]:
        return self._core.can_transform(target_frame, source_frame, time_ns(time))

    def can_transform_full_core(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str
    ) -> tuple[bool, str]:
        return self._core.can_transform_full(
            target_frame, time_ns(target_time), source_frame, time_ns(source_time), fixed_frame
        )

    def get_latest_common_time(self, target_frame: str, source_frame: str) -> Any:
        from rclpy.time import Time

        return Time(nanoseconds=self._core.latest_common_time(target_frame, source_frame))

    def all_frames_as_yaml(self) -> str:
        return self._core.all_frames_as_yaml()

    def all_frames_as_string(self) -> str:
        return self._core.all_frames_as_string()

    def clear(self) -> None:
        self._core.clear()

    def _frameExists(self, frame_id: str) -> bool:
        return self._core.frame_exists(frame_id)

    def _getFrameStrings(self) -> list[str]:
        return self._core.frame_names()


class TypeException(Exception):
    """A type with no registered transform or conversion."""

    def __init__(self, errstr: str) -> None:
        super().__init__(errstr)
        self.errstr = errstr


class NotImplementedException(Exception):
    def __init__(self) -> None:
        super().__init__("CanTransform or LookupTransform not implemented")
        self.errstr = "CanTransform or LookupTransform not implemented"


class TransformRegistration:
    """Message type → do_transform function (one process-wide table, as tf2_ros's)."""

    _type_map: ClassVar[dict[Any, Callable[[Any, Any], Any]]] = {}

    def add(self, key: Any, callback: Callable[[Any, Any], Any]) -> None:
        TransformRegistration._type_map[key] = callback

    def get(self, key: Any) -> Callable[[Any, Any], Any]:
        if key not in TransformRegistration._type_map:
            raise TypeException(f"Type {key} is not loaded or supported")
        return TransformRegistration._type_map[key]

    def print_me(self) -> None:
        print(TransformRegistration._type_map)


class ConvertRegistration:
    _to_msg: ClassVar[dict[Any, Callable[[Any], Any]]] = {}
    _from_msg: ClassVar[dict[Any, Callable[[Any], Any]]] = {}
    _convert: ClassVar[dict[Any, Callable[[Any], Any]]] = {}

    def add_from_msg(self, key: Any, callback: Callable[[Any], Any]) -> None:
        ConvertRegistration._from_msg[key] = callback

    def add_to_msg(self, key: Any, callback: Callable[[Any], Any]) -> None:
        ConvertRegistration._to_msg[key] = callback

    def add_convert(self, key: Any, callback: Callable[[Any], Any]) -> None:
        ConvertRegistration._convert[key] = callback

    @staticmethod
    def _get(table: dict[Any, Callable[[Any], Any]], key: Any) -> Callable[[Any], Any]:
        if key not in table:
            raise TypeException(f"Type {key} is not loaded or supported")
        return table[key]

    def get_from_msg(self, key: Any) -> Callable[[Any], Any]:
        return self._get(ConvertRegistration._from_msg, key)

    def get_to_msg(self, key: Any) -> Callable[[Any], Any]:
        return self._get(ConvertRegistration._to_msg, key)

    def get_convert(self, key: Any) -> Callable[[Any], Any]:
        return self._get(ConvertRegistration._convert, key)


def convert(a: Any, b_type: Any) -> Any:
    c = ConvertRegistration()
    try:
        return c.get_convert((type(a), b_type))(a)
    except TypeException:
        if type(a) is b_type:
            return deepcopy(a)
        return c.get_from_msg(b_type)(c.get_to_msg(type(a))(a))


class BufferInterface:
    """transform()/transform_full() of stamped messages through the registered do_transform functions."""

    def __init__(self) -> None:
        self.registration = TransformRegistration()

    def transform(self, object_stamped: Any, target_frame: str, timeout: Any = None, new_type: Any = None) -> Any:
        do_transform = self.registration.get(type(object_stamped))
        header = object_stamped.header
        result = do_transform(
            object_stamped, self.lookup_transform(target_frame, header.frame_id, header.stamp, _duration(timeout))
        )
        return result if new_type is None else convert(result, new_type)

    def transform_full(
        self, object_stamped: Any, target_frame: str, target_time: Any, fixed_frame: str, timeout: Any = None,
        new_type: Any = None,
    ) -> Any:
        do_transform = self.registration.get(type(object_stamped))
        header = object_stamped.header
        result = do_transform(
            object_stamped,
            self.lookup_transform_full(
                target_frame, target_time, header.frame_id, header.stamp, fixed_frame, _duration(timeout)
            ),
        )
        return result if new_type is None else convert(result, new_type)

    def lookup_transform(self, target_frame: str, source_frame: str, time: Any, timeout: Any = None) -> Any:
        raise NotImplementedException()

    def lookup_transform_full(self, *args: Any, **kwargs: Any) -> Any:
        raise NotImplementedException()

    def can_transform(self, *args: Any, **kwargs: Any) -> bool:
        raise NotImplementedException()

    def can_transform_full(self, *args: Any, **kwargs: Any) -> bool:
        raise NotImplementedException()


def _duration(d: Any) -> Any:
    if d is not None:
        return d
    from rclpy.duration import Duration

    return Duration()


class Buffer(BufferCore, BufferInterface):
    """tf2_ros.Buffer: lookups that may wait (polling on the system clock, blocking the caller, as
    tf2_ros does), futures that complete when data arrives, and `tf2_frames` when given a node."""

    def __init__(self, cache_time: Any = None, node: Any = None) -> None:
        BufferCore.__init__(self, cache_time)
        BufferInterface.__init__(self)
        self._new_data_callbacks: list[Callable[[], None]] = []
        self._callbacks_to_remove: list[Callable[[], None]] = []
        self._callbacks_lock = threading.RLock()
        import rclpy.clock

        if node is not None:
            try:
                from tf2_msgs.srv import FrameGraph
            except ImportError:
                FrameGraph = None
            if FrameGraph is not None:
                self.srv = node.create_service(
                    FrameGraph, "tf2_frames", lambda req, res: FrameGraph.Response(frame_yaml=self.all_frames_as_yaml())
                )
            self.clock = node.get_clock()
        else:
            self.clock = rclpy.clock.Clock()
        from rclpy.clock import JumpThreshold
        from rclpy.duration import Duration

        # A jump back in ROS time (a bag looping, a simulation reset) makes the stored past meaningless.
        threshold = JumpThreshold(min_forward=None, min_backward=Duration(seconds=-1), on_clock_change=True)
        self.jump_handle = self.clock.create_jump_callback(threshold, post_callback=self._time_jump)

    def _time_jump(self, time_jump: Any) -> None:
        import rclpy.logging

        rclpy.logging.get_logger("tf2_buffer").warning("Detected jump back in time. Clearing tf buffer.")
        self.clear()

    def set_transform(self, transform: Any, authority: str) -> None:
        super().set_transform(transform, authority)
        self._call_new_data_callbacks()

    def set_transform_static(self, transform: Any, authority: str) -> None:
        super().set_transform_static(transform, authority)
        self._call_new_data_callbacks()

    def _call_new_data_callbacks(self) -> None:
        with self._callbacks_lock:
            for callback in list(self._new_data_callbacks):
                callback()
            for callback in self._callbacks_to_remove:
                if callback in self._new_data_callbacks:
                    self._new_data_callbacks.remove(callback)
            self._callbacks_to_remove.clear()

    def _remove_callback(self, callback: Callable[[], None]) -> None:
        with self._callbacks_lock:
            self._callbacks_to_remove.append(callback)

    def lookup_transform(self, target_frame: str, source_frame: str, time: Any, timeout: Any = None) -> Any:
        self.can_transform(target_frame, source_frame, time, timeout)
        return self.lookup_transform_core(target_frame, source_frame, time)

    async def lookup_transform_async(self, target_frame: str, source_frame: str, time: Any) -> Any:
        await self.wait_for_transform_async(target_frame, source_frame, time)
        return self.lookup_transform_core(target_frame, source_frame, time)

    def lookup_transform_full(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str,
        timeout: Any = None,
    ) -> Any:
        self.can_transform_full(target_frame, target_time, source_frame, source_time, fixed_frame, timeout)
        return self.lookup_transform_full_core(target_frame, target_time, source_frame, source_time, fixed_frame)

    async def lookup_transform_full_async(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str
    ) -> Any:
        await self.wait_for_transform_full_async(target_frame, target_time, source_frame, source_time, fixed_frame)
        return self.lookup_transform_full_core(target_frame, target_time, source_frame, source_time, fixed_frame)

    def _wait(self, check: Callable[[], tuple[bool, str]], timeout: Any) -> tuple[bool, str]:
        wait_ns = duration_ns(timeout)
        if wait_ns > 0:
            deadline = _time.monotonic() + wait_ns / 1e9
            while _time.monotonic() < deadline and not check()[0]:
                _time.sleep(WAIT_POLL_S)
        return check()

    def can_transform(
        self, target_frame: str, source_frame: str, time: Any, timeout: Any = None, return_debug_tuple: bool = False
    ) -> Any:
        result = self._wait(lambda: self.can_transform_core(target_frame, source_frame, time), timeout)
        return result if return_debug_tuple else result[0]

    def can_transform_full(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str,
        timeout: Any = None, return_debug_tuple: bool = False,
    ) -> Any:
        result = self._wait(
            lambda: self.can_transform_full_core(target_frame, target_time, source_frame, source_time, fixed_frame),
            timeout,
        )
        return result if return_debug_tuple else result[0]

    def _future_when(self, ready: Callable[[], bool], value: Callable[[], Any]) -> Any:
        from rclpy.task import Future

        fut = Future()
        if ready():
            fut.set_result(value())
            return fut

        def on_new_data() -> None:
            if fut.done():
                return
            try:
                if ready():
                    fut.set_result(value())
            except TransformException as e:
                fut.set_exception(e)

        with self._callbacks_lock:
            self._new_data_callbacks.append(on_new_data)
        fut.add_done_callback(lambda _: self._remove_callback(on_new_data))
        return fut

    def wait_for_transform_async(self, target_frame: str, source_frame: str, time: Any) -> Any:
        """A Future whose result is the transform, once the buffer can give it."""
        return self._future_when(
            lambda: self.can_transform_core(target_frame, source_frame, time)[0],
            lambda: self.lookup_transform_core(target_frame, source_frame, time),
        )

    def wait_for_transform_full_async(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str
    ) -> Any:
        args = (target_frame, target_time, source_frame, source_time, fixed_frame)
        return self._future_when(
            lambda: self.can_transform_full_core(*args)[0], lambda: self.lookup_transform_full_core(*args)
        )


def _tf_qos(depth: int, latched: bool) -> Any:
    from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile

    return QoSProfile(
        depth=depth,
        durability=DurabilityPolicy.TRANSIENT_LOCAL if latched else DurabilityPolicy.VOLATILE,
        history=HistoryPolicy.KEEP_LAST,
    )


class TransformListener:
    """Fills `buffer` from /tf and /tf_static (its own reentrant callback group; with `spin_thread` a
    thread of its own spins the node)."""

    def __init__(
        self, buffer: Buffer, node: Any, *, spin_thread: bool = False, qos: Any = None, static_qos: Any = None
    ) -> None:
        from rclpy.callback_groups import ReentrantCallbackGroup
        from tf2_msgs.msg import TFMessage

        self.buffer = buffer
        self.node = node
        self.group = ReentrantCallbackGroup()
        self.tf_sub = node.create_subscription(
            TFMessage, TF_TOPIC, self.callback, qos or _tf_qos(100, False), callback_group=self.group
        )
        self.tf_static_sub = node.create_subscription(
            TFMessage, TF_STATIC_TOPIC, self.static_callback, static_qos or _tf_qos(100, True),
            callback_group=self.group,
        )
        self.dedicated_listener_thread: threading.Thread | None = None
        if spin_thread:
            from rclpy.executors import SingleThreadedExecutor

            self.executor = SingleThreadedExecutor()

            def run() -> None:
                self.executor.add_node(self.node)
                self.executor.spin()
                self.executor.remove_node(self.node)

            self.dedicated_listener_thread = threading.Thread(target=run, daemon=True)
            self.dedicated_listener_thread.start()

    def __del__(self) -> None:
        if self.dedicated_listener_thread is not None:
            self.executor.shutdown()

    def unregister(self) -> None:
        self.node.destroy_subscription(self.tf_sub)
        self.node.destroy_subscription(self.tf_static_sub)

    def callback(self, data: Any) -> None:
        for transform in data.transforms:
            self.buffer.set_transform(transform, "default_authority")

    def static_callback(self, data: Any) -> None:
        for transform in data.transforms:
            self.buffer.set_transform_static(transform, "default_authority")


def _as_list(transform: Any) -> list[Any]:
    if isinstance(transform, list):
        return transform
    if isinstance(transform, Iterable) and not hasattr(transform, "child_frame_id"):
        return list(transform)
    return [transform]


class TransformBroadcaster:
    """Publishes TransformStamped messages on /tf (depth 100)."""

    def __init__(self, node: Any, qos: Any = None) -> None:
        from tf2_msgs.msg import TFMessage

        self._msg_type = TFMessage
        self.pub_tf = node.create_publisher(TFMessage, TF_TOPIC, qos or _tf_qos(100, False))

    def sendTransform(self, transform: Any) -> None:
        self.pub_tf.publish(self._msg_type(transforms=_as_list(transform)))


class StaticTransformBroadcaster:
    """Publishes on /tf_static (transient local, depth 1) every static transform sent so far, the newest
    of each child frame, so a late listener gets them all in one message."""

    def __init__(self, node: Any, qos: Any = None) -> None:
        from tf2_msgs.msg import TFMessage

        self._msg_type = TFMessage
        self.pub_tf = node.create_publisher(TFMessage, TF_STATIC_TOPIC, qos or _tf_qos(1, True))
        self.net_message = TFMessage()
        self._by_child: dict[str, Any] = {}

    def sendTransform(self, transform: Any) -> None:
        for t in _as_list(transform):
            self._by_child[t.child_frame_id] = t
        self.net_message = self._msg_type(transforms=list(self._by_child.values()))
        self.pub_tf.publish(self.net_message)
