"""rclpy.event_handler: an endpoint's QoS events, run by the executor as rclpy's EventHandler waitables.

rmw_zenoh reports incompatible QoS, matched endpoints and lost messages; diffctl adds what it does not
(deadlines missed, liveliness lost and changed, lifespan), which ROS users' QoS demos expect, as DDS counts them
(`qos_status.py`). `DIFFCTL_QOS_EVENTS=rmw_zenoh` restores rmw_zenoh's behaviour: a deadline or liveliness
callback raises UnsupportedEventTypeError and a lifespan expires nothing.

Incompatible QoS: rmw_zenoh connects every pair of endpoints whatever their QoS, so nothing is lost on the
wire; the default callbacks still report a pair that DDS would refuse (a best-effort publisher and a reliable
subscription, …), with rclpy's text.
"""

from __future__ import annotations

import dataclasses
import enum
import os
import threading
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from diffctl.bus import wire
from diffctl.client import waiting
from diffctl.client.exceptions import UnsupportedEventTypeError
from diffctl.client.qos import from_wire, incompatible_policies, qos_policy_name_from_kind
from diffctl.client.qos_status import ChangedLiveliness, LostLiveliness, LostMessages, MissedDeadlines
from diffctl.client.ros_logging import get_logger
from diffctl.client.timer import await_or_execute
from diffctl.client.waitable import NumberOfEntities, Waitable

QOS_EVENTS_ENV = "DIFFCTL_QOS_EVENTS"


def dds_events() -> bool:
    """Whether deadline, liveliness and lifespan work (the default) or are refused as rmw_zenoh refuses them."""
    return os.environ.get(QOS_EVENTS_ENV, "dds") != "rmw_zenoh"


class QoSPublisherEventType(enum.IntEnum):
    RCL_PUBLISHER_OFFERED_DEADLINE_MISSED = 0
    RCL_PUBLISHER_LIVELINESS_LOST = 1
    RCL_PUBLISHER_OFFERED_INCOMPATIBLE_QOS = 2
    RCL_PUBLISHER_INCOMPATIBLE_TYPE = 3
    RCL_PUBLISHER_MATCHED = 4


class QoSSubscriptionEventType(enum.IntEnum):
    RCL_SUBSCRIPTION_REQUESTED_DEADLINE_MISSED = 0
    RCL_SUBSCRIPTION_LIVELINESS_CHANGED = 1
    RCL_SUBSCRIPTION_REQUESTED_INCOMPATIBLE_QOS = 2
    RCL_SUBSCRIPTION_MESSAGE_LOST = 3
    RCL_SUBSCRIPTION_INCOMPATIBLE_TYPE = 4
    RCL_SUBSCRIPTION_MATCHED = 5


class _BoundEnumType(enum.EnumType):
    def __repr__(cls) -> str:
        # pybind11's enums are classes: `<class 'rclpy._rclpy_pybind11.rmw_qos_policy_kind_t'>`, not `<enum …>`
        return f"<class '{cls.__module__}.{cls.__qualname__}'>"


class rmw_qos_policy_kind_t(enum.IntEnum, metaclass=_BoundEnumType):
    """The kind in an incompatible-QoS event, as rclpy's pybind11 enum: compares equal to QoSPolicyKind's
    values, but prints as `rmw_qos_policy_kind_t.RMW_QOS_POLICY_DURABILITY` (what the QoS demos log)."""

    RMW_QOS_POLICY_INVALID = 1 << 0
    RMW_QOS_POLICY_DURABILITY = 1 << 1
    RMW_QOS_POLICY_DEADLINE = 1 << 2
    RMW_QOS_POLICY_LIVELINESS = 1 << 3
    RMW_QOS_POLICY_RELIABILITY = 1 << 4
    RMW_QOS_POLICY_HISTORY = 1 << 5
    RMW_QOS_POLICY_LIFESPAN = 1 << 6
    RMW_QOS_POLICY_DEPTH = 1 << 7
    RMW_QOS_POLICY_LIVELINESS_LEASE_DURATION = 1 << 8
    RMW_QOS_POLICY_AVOID_ROS_NAMESPACE_CONVENTIONS = 1 << 9

    @classmethod
    def _missing_(cls, value: object) -> rmw_qos_policy_kind_t | None:
        # pybind11 holds any int; one that names no kind (a status nobody filled: 0) prints as `???`.
        if not isinstance(value, int):
            return None
        member = int.__new__(cls, value)
        member._name_ = "???"
        member._value_ = value
        return member

    def __str__(self) -> str:
        return f"{type(self).__name__}.{self._name_}"

    def __format__(self, spec: str) -> str:
        return format(str(self), spec)


rmw_qos_policy_kind_t.__module__ = "rclpy._rclpy_pybind11"
_KIND_UNSET = rmw_qos_policy_kind_t(0)


@dataclass(frozen=True)
class QoSRequestedIncompatibleQoSInfo:
    total_count: int = 0
    total_count_change: int = 0
    last_policy_kind: rmw_qos_policy_kind_t = _KIND_UNSET


QoSOfferedIncompatibleQoSInfo = QoSRequestedIncompatibleQoSInfo


@dataclass(frozen=True)
class _CountInfo:
    total_count: int = 0
    total_count_change: int = 0


class QoSOfferedDeadlineMissedInfo(_CountInfo):
    pass


class QoSRequestedDeadlineMissedInfo(_CountInfo):
    pass


class QoSLivelinessLostInfo(_CountInfo):
    pass


class QoSMessageLostInfo(_CountInfo):
    pass


class IncompatibleTypeInfo(_CountInfo):
    pass


@dataclass(frozen=True)
class QoSLivelinessChangedInfo:
    alive_count: int = 0
    not_alive_count: int = 0
    alive_count_change: int = 0
    not_alive_count_change: int = 0


@dataclass(frozen=True)
class QoSMatchedInfo:
    total_count: int = 0
    total_count_change: int = 0
    current_count: int = 0
    current_count_change: int = 0


def _bound_struct_repr(self: object) -> str:
    # pybind11's default for a bound struct: what `print(event)` or an f-string of an event shows in rclpy.
    cls = type(self)
    return f"<{cls.__module__}.{cls.__qualname__} object at {id(self):#x}>"


def _no_such_field(self: object, name: str, cut: int) -> AttributeError:
    # CPython names the type by its C-level name (pybind11's is the dotted one), cut to 50 characters on a
    # read and to 100 on a write.
    cls = type(self)
    return AttributeError(f"'{f'{cls.__module__}.{cls.__qualname__}'[:cut]}' object has no attribute '{name}'")


def _bound_struct_getattr(self: object, name: str) -> Any:
    raise _no_such_field(self, name, 50)


def _bound_struct_setattr(self: object, name: str, value: Any) -> None:
    # rclpy binds the status fields read-only (a callback reading the wrong kind's field, as the liveliness
    # demo's publisher callback does, fails with these words).
    if name in getattr(type(self), "__dataclass_fields__", {}):
        raise AttributeError(f"property of '{type(self).__qualname__}' object has no setter")
    raise _no_such_field(self, name, 100)


# rclpy's info classes are rmw's status structs as pybind11 binds them: they carry rmw's names.
for _cls, _rmw in ((QoSRequestedIncompatibleQoSInfo, "rmw_requested_qos_incompatible_event_status_t"),
                   (QoSOfferedDeadlineMissedInfo, "rmw_offered_deadline_missed_status_t"),
                   (QoSRequestedDeadlineMissedInfo, "rmw_requested_deadline_missed_status_t"),
                   (QoSLivelinessLostInfo, "rmw_liveliness_lost_status_t"),
                   (QoSLivelinessChangedInfo, "rmw_liveliness_changed_status_t"),
                   (QoSMessageLostInfo, "rmw_message_lost_status_t"),
                   (IncompatibleTypeInfo, "rmw_incompatible_type_status_t"),
                   (QoSMatchedInfo, "rmw_matched_status_t")):
    _cls.__name__ = _cls.__qualname__ = _rmw
    _cls.__module__ = "rclpy._rclpy_pybind11"
    _cls.__repr__ = _bound_struct_repr  # type: ignore[method-assign]
    _cls.__getattr__ = _bound_struct_getattr  # type: ignore[attr-defined]
    _cls.__setattr__ = _bound_struct_setattr  # type: ignore[method-assign,assignment]


QoSSubscriptionMatchedInfo = QoSMatchedInfo
QoSPublisherMatchedInfo = QoSMatchedInfo


class EventHandler(Waitable):
    """One event kind of one endpoint, run by the executor. Events come either posted (`post(info)`, from a
    graph watch) or from a status read when due (`status`, with `make_info` building rclpy's info from it)."""

    def __init__(self, *, callback_group: Any, callback: Callable[[Any], Any], event_type: Any = None,
                 parent_impl: Any = None) -> None:
        super().__init__(callback_group)
        self.event_type = event_type
        self.callback = callback
        self._pending: list[Any] = []
        self._lock = threading.Lock()
        self.status: Any = None
        self.make_info: Callable[..., Any] = _CountInfo
        self._watch: Any = None

    def post(self, info: Any) -> None:
        with self._lock:
            self._pending.append(info)
        waiting.notify()

    def is_ready(self, wait_set: Any = None) -> bool:
        if self._pending:
            return True
        return self.status is not None and self.status.pending(time.monotonic_ns())

    def take_data(self) -> Any:
        if self.status is not None:
            now = time.monotonic_ns()
            return self.make_info(*self.status.read(now)) if self.status.pending(now) else None
        # An rmw event is a status: what happened since the last take comes as one, its changes summed.
        with self._lock:
            pending, self._pending = self._pending, []
        if not pending:
            return None
        last = pending[-1]
        summed = {field: sum(getattr(p, field) for p in pending)
                  for field in ("total_count_change", "current_count_change") if hasattr(last, field)}
        return dataclasses.replace(last, **summed) if len(pending) > 1 else last

    async def execute(self, taken_data: Any) -> None:
        if taken_data:
            await await_or_execute(self.callback, taken_data)

    def _due_in_s(self) -> float | None:
        if self.status is None:
            return None
        due = self.status.due_in_ns(time.monotonic_ns())
        return None if due is None else due / 1e9

    def get_num_entities(self) -> NumberOfEntities:
        return NumberOfEntities(num_events=1)

    def destroy(self) -> None:
        if self._watch is not None:
            self._watch.close()


class QoSEventHandler(EventHandler):
    """rclpy's older name of EventHandler, deprecated as there."""

    def __init_subclass__(cls, **kwargs: Any) -> None:
        warnings.warn("QoSEventHandler foo is deprecated, use EventHandler instead.", DeprecationWarning,
                      stacklevel=2)
        super().__init_subclass__(**kwargs)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        warnings.warn("QoSEventHandler is deprecated, use EventHandler instead.", DeprecationWarning, stacklevel=2)
        super().__init__(*args, **kwargs)


class _GraphWatch:
    """Calls `on_graph(event, entity)` for the other side's endpoints of the endpoint's topic, until closed."""

    def __init__(self, endpoint: Any, *, is_publisher: bool, on_graph: Callable[[str, wire.Entity], None]) -> None:
        self._endpoint = endpoint
        self._kind = wire.KIND_SUB if is_publisher else wire.KIND_PUB
        self._on = on_graph
        self._closed = False
        endpoint._node._bus.graph.add_listener(self._on_graph)

    def _on_graph(self, event: str, ent: wire.Entity) -> None:
        if not self._closed and ent.kind == self._kind and ent.topic == self._endpoint._bus_topic:
            self._on(event, ent)

    def close(self) -> None:
        self._closed = True


def _incompatible_qos(endpoint: Any, handler: EventHandler, *, is_publisher: bool) -> _GraphWatch:
    """Counts endpoints of the other side whose QoS DDS would not match with this one's."""
    seen: set[str] = set()
    count = [0]

    def on_graph(event: str, ent: wire.Entity) -> None:
        if event != "put" or ent.token in seen:
            return
        seen.add(ent.token)
        other = from_wire(ent.qos_profile)
        pub, sub = (endpoint.qos_profile, other) if is_publisher else (other, endpoint.qos_profile)
        bad = incompatible_policies(pub, sub)
        if bad:
            count[0] += 1
            handler.post(QoSRequestedIncompatibleQoSInfo(count[0], 1, rmw_qos_policy_kind_t(bad[-1][0])))

    return _GraphWatch(endpoint, is_publisher=is_publisher, on_graph=on_graph)


def _incompatible_type(endpoint: Any, handler: EventHandler, *, is_publisher: bool) -> _GraphWatch:
    """rmw_zenoh's incompatible-type status: endpoints of the other side of the topic with another type."""
    seen: set[str] = set()

    def on_graph(event: str, ent: wire.Entity) -> None:
        if event == "put" and ent.type != endpoint._bus.type and ent.token not in seen:
            seen.add(ent.token)
            handler.post(IncompatibleTypeInfo(len(seen), 1))

    return _GraphWatch(endpoint, is_publisher=is_publisher, on_graph=on_graph)


def _matched(endpoint: Any, handler: EventHandler, *, is_publisher: bool) -> _GraphWatch:
    """rmw's matched status from the graph: endpoints of the other side of the topic with the same type."""
    matched: set[str] = set()
    total = [0]

    def on_graph(event: str, ent: wire.Entity) -> None:
        if ent.type != endpoint._bus.type:
            return
        if event == "put" and ent.token not in matched:
            matched.add(ent.token)
            total[0] += 1
            handler.post(QoSMatchedInfo(total[0], 1, len(matched), 1))
        elif event == "delete" and ent.token in matched:
            matched.discard(ent.token)
            handler.post(QoSMatchedInfo(total[0], 0, len(matched), -1))

    return _GraphWatch(endpoint, is_publisher=is_publisher, on_graph=on_graph)


def _ns(duration: Any) -> int | None:
    ns = duration.nanoseconds
    return ns if 0 < ns < 2**63 - 1 else None


class SubscriptionEventCallbacks:
    def __init__(self, *, deadline: Any = None, incompatible_qos: Any = None, liveliness: Any = None,
                 message_lost: Any = None, incompatible_type: Any = None, matched: Any = None,
                 use_default_callbacks: bool = True) -> None:
        self.deadline = deadline
        self.incompatible_qos = incompatible_qos
        self.liveliness = liveliness
        self.message_lost = message_lost
        self.incompatible_type = incompatible_type
        self.matched = matched
        self.use_default_callbacks = use_default_callbacks

    def create_event_handlers(self, callback_group: Any, subscription: Any, topic_name: str) -> list[EventHandler]:
        return _create(self, callback_group, subscription, topic_name, is_publisher=False)


class PublisherEventCallbacks:
    def __init__(self, *, deadline: Any = None, liveliness: Any = None, incompatible_qos: Any = None,
                 incompatible_type: Any = None, matched: Any = None, use_default_callbacks: bool = True) -> None:
        self.deadline = deadline
        self.liveliness = liveliness
        self.incompatible_qos = incompatible_qos
        self.incompatible_type = incompatible_type
        self.matched = matched
        self.use_default_callbacks = use_default_callbacks

    def create_event_handlers(self, callback_group: Any, publisher: Any, topic_name: str) -> list[EventHandler]:
        return _create(self, callback_group, publisher, topic_name, is_publisher=True)


def _create(cbs: Any, callback_group: Any, endpoint: Any, topic_name: str, *, is_publisher: bool) -> list[EventHandler]:
    """The endpoint's handlers in rclpy's order; statuses the endpoint must feed go on `endpoint.qos_statuses`."""
    if (cbs.deadline or cbs.liveliness) and not dds_events():
        raise UnsupportedEventTypeError("Failed to create event handler: event type is not supported by rmw_zenoh_cpp")
    kinds = QoSPublisherEventType if is_publisher else QoSSubscriptionEventType
    prefix = "RCL_PUBLISHER_" if is_publisher else "RCL_SUBSCRIPTION_"
    handlers: list[EventHandler] = []

    def add(callback: Any, kind: str, make_info: Any = None) -> EventHandler:
        h = EventHandler(callback_group=callback_group, callback=callback, event_type=kinds[prefix + kind],
                         parent_impl=endpoint)
        if make_info is not None:
            h.make_info = make_info
        handlers.append(h)
        return h

    profile = endpoint.qos_profile
    statuses = endpoint.qos_statuses
    if cbs.deadline:
        h = add(cbs.deadline, "OFFERED_DEADLINE_MISSED" if is_publisher else "REQUESTED_DEADLINE_MISSED",
                QoSOfferedDeadlineMissedInfo if is_publisher else QoSRequestedDeadlineMissedInfo)
        period = _ns(profile.deadline)
        if period is not None:  # an infinite deadline is never missed
            h.status = statuses.deadline = MissedDeadlines(period)
    logger = get_logger(endpoint._node.get_logger().name)
    if is_publisher and cbs.liveliness:
        h = add(cbs.liveliness, "LIVELINESS_LOST", QoSLivelinessLostInfo)
        lease = _ns(profile.liveliness_lease_duration)
        if lease is not None and statuses.manual_liveliness:  # an AUTOMATIC publisher is alive while it exists
            h.status = statuses.lost = LostLiveliness(lease)
    callback = cbs.incompatible_qos
    if callback is None and cbs.use_default_callbacks:
        if is_publisher:
            def _default_incompatible_qos_callback(event: Any) -> None:
                logger.warn(f"New subscription discovered on topic '{topic_name}', requesting incompatible QoS. "
                            "No messages will be sent to it. "
                            f"Last incompatible policy: {qos_policy_name_from_kind(event.last_policy_kind)}")
        else:
            def _default_incompatible_qos_callback(event: Any) -> None:
                logger.warn(f"New publisher discovered on topic '{topic_name}', offering incompatible QoS. "
                            "No messages will be received from it. "
                            f"Last incompatible policy: {qos_policy_name_from_kind(event.last_policy_kind)}")
        callback = _default_incompatible_qos_callback
    if callback is not None:
        h = add(callback, "OFFERED_INCOMPATIBLE_QOS" if is_publisher else "REQUESTED_INCOMPATIBLE_QOS")
        h._watch = _incompatible_qos(endpoint, h, is_publisher=is_publisher)
    if not is_publisher:
        if cbs.liveliness:
            h = add(cbs.liveliness, "LIVELINESS_CHANGED", QoSLivelinessChangedInfo)
            h.status = statuses.changed = ChangedLiveliness()
            h._watch = statuses.watch_writers(endpoint)
        if cbs.message_lost:
            h = add(cbs.message_lost, "MESSAGE_LOST", QoSMessageLostInfo)
            h.status = statuses.lost_messages = LostMessages()
    callback = cbs.incompatible_type
    if callback is None and cbs.use_default_callbacks:
        def _default_incompatible_type_callback(event: Any) -> None:
            logger.warn(f"Incompatible type on topic '{topic_name}', no messages will be sent to it.")
        callback = _default_incompatible_type_callback
    if callback is not None:
        h = add(callback, "INCOMPATIBLE_TYPE", IncompatibleTypeInfo)
        h._watch = _incompatible_type(endpoint, h, is_publisher=is_publisher)
    if cbs.matched:
        h = add(cbs.matched, "MATCHED")
        h._watch = _matched(endpoint, h, is_publisher=is_publisher)
    return handlers

