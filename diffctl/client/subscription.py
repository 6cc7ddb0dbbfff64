"""rclpy.subscription.Subscription: samples queued by Zenoh's thread (KEEP_LAST depth), taken by an executor."""

from __future__ import annotations

import collections
import enum
import inspect
import itertools
import time
from collections.abc import Callable
from typing import Any

from diffctl.bus import wire
from diffctl.client import waiting
from diffctl.client.destroyable import Handle
from diffctl.client.endpoint_statuses import EndpointStatuses
from diffctl.client.event_handler import dds_events
from diffctl.client.exceptions import InvalidHandle
from diffctl.client.interfaces import deserialize
from diffctl.client.node_entity import NodeEntity
from diffctl.client.qos import HistoryPolicy
from diffctl.client.timer import await_or_execute
from diffctl.errors import MessageError


def _attachment(sample: Any) -> tuple[int, int, bytes]:
    """(publication sequence number, source timestamp, publisher GID) from rmw_zenoh's attachment."""
    try:
        return wire.unpack_attachment(sample.attachment.to_bytes())
    except (MessageError, AttributeError):
        return 0, 0, b""


_BAD_CALLBACK = ("Subscription.__init__(): callback should be either be callable with one argument(to get only the "
                 "message) or two (to get message and message info)")


class SubscriptionHandle(Handle):
    """A subscription's `handle`, which also takes messages as rclpy's binding does."""

    __slots__ = ()

    def take_message(self, msg_type: Any, raw: bool) -> tuple[Any, dict[str, int]] | None:
        sub = self._owner()
        if sub is None or not self._valid():
            raise InvalidHandle("cannot use Destroyable because destruction was requested")
        return sub._take_message(msg_type, raw)


class Subscription(NodeEntity):
    class CallbackType(enum.Enum):
        MessageOnly = 0
        WithMessageInfo = 1

    def __init__(self, node: Any, msg_type: Any, topic: str, callback: Callable[..., Any], callback_group: Any,
                 qos_profile: Any, raw: bool, *, event_callbacks: Any) -> None:
        self._node = node
        self.msg_type = msg_type
        self.topic = topic
        self.callback_group = callback_group
        self.qos_profile = qos_profile
        self.raw = raw
        self._executor_event = False
        self.callback = callback
        keep_all = qos_profile.history == HistoryPolicy.KEEP_ALL
        depth = qos_profile.depth if qos_profile.depth > 0 else 42
        # (zenoh.Sample, reception number): a bounded deque drops the oldest as KEEP_LAST does
        self._queue: collections.deque[tuple[Any, int]] = collections.deque(maxlen=None if keep_all else depth)
        self._rx_seq = itertools.count(1)
        self._bus: Any = None
        self._bus_topic = ""
        self._destroyed = False
        self._event_callbacks = event_callbacks
        self.event_handlers: list[Any] = []
        self._on_arrival: Callable[[bytes, int], None] | None = None
        lifespan_ns = qos_profile.lifespan.nanoseconds
        self._lifespan_ns = lifespan_ns if 0 < lifespan_ns < 2**63 - 1 and dds_events() else None

    def _attach(self, bus_sub: Any) -> None:
        self._bus = bus_sub
        self._bus_topic = bus_sub.topic
        self.qos_statuses = EndpointStatuses(self.qos_profile)
        self.event_handlers = self._event_callbacks.create_event_handlers(self.callback_group, self, self.topic)
        self._on_arrival = self.qos_statuses.arrival_hook()

    def _on_sample(self, sample: Any) -> None:
        # Zenoh's thread, once per sample whether or not it is ever taken: the sample is queued as it came,
        # read when an executor takes it. An executor looks at every queue before it sleeps, so only the sample
        # that makes a queue non-empty has to wake one. The length is read after the append: read before, an
        # executor could empty the queue in between and sleep past this sample.
        if sample.attachment is None:  # rmw_zenoh drops these on arrival too; diffctl says so
            self._node._bus.throttled(f"noatt{self._bus_topic}",
                                      f"dropped a sample on {self._bus_topic} without rmw_zenoh attachment")
            return
        queue = self._queue
        queue.append((sample, next(self._rx_seq)))
        if self._on_arrival is not None:
            seq, _, gid = _attachment(sample)
            self._on_arrival(gid, seq)
        if len(queue) == 1:
            waiting.notify()

    @property
    def callback(self) -> Callable[..., Any]:
        return self._callback

    @callback.setter
    def callback(self, value: Callable[..., Any]) -> None:
        # One argument that binds: the message only; else two: the message and its info; else refused as rclpy
        # refuses it. (A callable without a signature is taken as rclpy took such callbacks before it checked.)
        try:
            signature = inspect.signature(value)
        except ValueError:
            signature = None
        except TypeError:  # not callable at all
            raise RuntimeError(_BAD_CALLBACK) from None
        kind = Subscription.CallbackType.WithMessageInfo
        if signature is not None:
            try:
                signature.bind(object())
                kind = Subscription.CallbackType.MessageOnly
            except TypeError:
                try:
                    signature.bind(object(), object())
                except TypeError:
                    raise RuntimeError(_BAD_CALLBACK) from None
        self._callback = value
        self._callback_type = kind

    def _ready(self) -> bool:
        return bool(self._queue)

    def _pop(self) -> tuple[Any, int, int, int] | None:
        """The oldest queued sample still within its lifespan: (sample, reception seq, publication seq, stamp)."""
        while True:
            try:
                sample, rx = self._queue.popleft()
            except IndexError:
                return None
            seq, stamp_ns, _ = _attachment(sample)
            # lifespan: a sample older than this subscription's lifespan is gone from its queue, as DDS's
            if self._lifespan_ns is None or time.time_ns() - stamp_ns <= self._lifespan_ns:
                return sample, rx, seq, stamp_ns

    def _take(self) -> Callable[[], Any] | None:
        popped = self._pop()
        if popped is None:
            return None
        sample, rx, seq, stamp_ns = popped
        data = sample.payload.to_bytes()
        try:
            msg = data if self.raw else deserialize(data, self.msg_type)
        except MessageError as e:  # a malformed sample is the sender's fault: dropped, the node goes on
            self._node._bus.throttled(f"bad{self._bus_topic}", f"dropped a malformed sample on {self._bus_topic}: {e}")
            return None
        callback = self._callback
        if self._callback_type is Subscription.CallbackType.MessageOnly:
            args: tuple[Any, ...] = (msg,)
        else:
            args = (msg, {
                "source_timestamp": stamp_ns, "received_timestamp": time.time_ns(),
                "publication_sequence_number": seq, "reception_sequence_number": rx,
            })

        async def _execute() -> None:
            await await_or_execute(callback, *args)

        return _execute

    def _take_message(self, msg_type: Any, raw: bool) -> tuple[Any, dict[str, int]] | None:
        """The oldest queued sample as (message, info), or None: rclpy's `sub.handle.take_message`, by which
        custom executors and recorders take outside any executor (the executor's own path is `_take`)."""
        popped = self._pop()
        if popped is None:
            return None
        sample, rx, seq, stamp_ns = popped
        data = sample.payload.to_bytes()
        msg = data if raw else deserialize(data, msg_type)
        return msg, {"source_timestamp": stamp_ns, "received_timestamp": time.time_ns(),
                     "publication_sequence_number": seq, "reception_sequence_number": rx}

    @property
    def handle(self) -> Handle:
        handle = self.__dict__.get("_handle")
        if handle is None:
            handle = self.__dict__["_handle"] = SubscriptionHandle(self)
        return handle

    def get_publisher_count(self) -> int:
        return sum(1 for e in self._node._bus.graph.publishers(self._bus_topic) if e.type == self._bus.type)

    @property
    def topic_name(self) -> str:
        return self._bus_topic

    def destroy(self) -> None:
        self._node.destroy_subscription(self)

    def _destroy(self) -> None:
        if not self._destroyed:
            self._destroyed = True
            for h in self.event_handlers:
                h.destroy()
            if self._bus is not None:
                self._node._bus.destroy_subscription(self._bus)
