"""rclpy.event_handler: QoS event callbacks; incompatible QoS is found from the graph's endpoint profiles.

rmw_zenoh connects every pair of endpoints whatever their QoS, so nothing is lost on the wire; rclpy's
default callbacks still report a pair that DDS would refuse (a best-effort publisher and a reliable
subscription, …), with rclpy's text, when the executor runs the event.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from diffctl.bus import wire
from diffctl.client import waiting
from diffctl.client.exceptions import UnsupportedEventTypeError
from diffctl.client.qos import QoSPolicyKind, from_wire, incompatible_policies, qos_policy_name_from_kind
from diffctl.client.timer import await_or_execute
from diffctl.client.waitable import Waitable


@dataclass
class QoSRequestedIncompatibleQoSInfo:
    total_count: int = 0
    total_count_change: int = 0
    last_policy_kind: int = int(QoSPolicyKind.INVALID)


QoSOfferedIncompatibleQoSInfo = QoSRequestedIncompatibleQoSInfo


@dataclass
class IncompatibleTypeInfo:
    total_count: int = 0
    total_count_change: int = 0


@dataclass
class QoSMatchedInfo:
    total_count: int = 0
    total_count_change: int = 0
    current_count: int = 0
    current_count_change: int = 0


QoSSubscriptionMatchedInfo = QoSMatchedInfo
QoSPublisherMatchedInfo = QoSMatchedInfo


class EventHandler(Waitable):
    """One event kind of one endpoint: pending event payloads, run by the executor."""

    def __init__(self, *, callback_group: Any, callback: Callable[[Any], Any]) -> None:
        super().__init__(callback_group)
        self.callback = callback
        self._pending: list[Any] = []
        self._lock = threading.Lock()

    def post(self, info: Any) -> None:
        with self._lock:
            self._pending.append(info)
        waiting.notify()

    def is_ready(self, wait_set: Any = None) -> bool:
        return bool(self._pending)

    def take_data(self) -> Any:
        # An rmw event is a status: what happened since the last take comes as one, its changes summed.
        with self._lock:
            pending, self._pending = self._pending, []
        if not pending:
            return None
        last = pending[-1]
        for field in ("total_count_change", "current_count_change"):
            if hasattr(last, field):
                setattr(last, field, sum(getattr(p, field, 0) for p in pending))
        return last

    async def execute(self, taken_data: Any) -> None:
        if taken_data is not None:
            await await_or_execute(self.callback, taken_data)


class _IncompatibleQoSWatch:
    """Watches the graph for endpoints of the other side of a topic whose QoS DDS would not match."""

    def __init__(self, endpoint: Any, handler: EventHandler, *, is_publisher: bool) -> None:
        self._endpoint = endpoint
        self._handler = handler
        self._is_publisher = is_publisher
        self._count = 0
        self._seen: set[str] = set()
        self._closed = False
        endpoint._node._bus.graph.add_listener(self._on_graph)

    def _on_graph(self, event: str, ent: wire.Entity) -> None:
        ep = self._endpoint
        if self._closed or event != "put" or ent.topic != ep._bus_topic or ent.token in self._seen:
            return
        if ent.kind != (wire.KIND_SUB if self._is_publisher else wire.KIND_PUB):
            return
        self._seen.add(ent.token)
        other = from_wire(ent.qos_profile)
        pub, sub = (ep.qos_profile, other) if self._is_publisher else (other, ep.qos_profile)
        bad = incompatible_policies(pub, sub)
        if bad:
            self._count += 1
            self._handler.post(QoSRequestedIncompatibleQoSInfo(self._count, 1, int(bad[-1][0])))

    def close(self) -> None:
        self._closed = True


class _MatchedWatch:
    """rmw's matched status from the graph: endpoints of the other side of the topic with the same type."""

    def __init__(self, endpoint: Any, handler: EventHandler, *, is_publisher: bool) -> None:
        self._endpoint = endpoint
        self._handler = handler
        self._kind = wire.KIND_SUB if is_publisher else wire.KIND_PUB
        self._matched: set[str] = set()
        self._total = 0
        self._closed = False
        endpoint._node._bus.graph.add_listener(self._on_graph)

    def _on_graph(self, event: str, ent: wire.Entity) -> None:
        ep = self._endpoint
        if self._closed or ent.kind != self._kind or ent.topic != ep._bus_topic or ent.type != ep._bus.type:
            return
        if event == "put" and ent.token not in self._matched:
            self._matched.add(ent.token)
            self._total += 1
            self._handler.post(QoSMatchedInfo(self._total, 1, len(self._matched), 1))
        elif event == "delete" and ent.token in self._matched:
            self._matched.discard(ent.token)
            self._handler.post(QoSMatchedInfo(self._total, 0, len(self._matched), -1))

    def close(self) -> None:
        self._closed = True


class SubscriptionEventCallbacks:
    def __init__(self, *, deadline: Any = None, incompatible_qos: Any = None, liveliness: Any = None,
                 message_lost: Any = None, use_default_callbacks: bool = True, incompatible_type: Any = None,
                 matched: Any = None) -> None:
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
                 incompatible_type: Any = None, use_default_callbacks: bool = True, matched: Any = None) -> None:
        self.deadline = deadline
        self.liveliness = liveliness
        self.incompatible_qos = incompatible_qos
        self.incompatible_type = incompatible_type
        self.matched = matched
        self.use_default_callbacks = use_default_callbacks

    def create_event_handlers(self, callback_group: Any, publisher: Any, topic_name: str) -> list[EventHandler]:
        return _create(self, callback_group, publisher, topic_name, is_publisher=True)


def _create(cbs: Any, callback_group: Any, endpoint: Any, topic_name: str, *, is_publisher: bool) -> list[EventHandler]:
    if cbs.deadline is not None or cbs.liveliness is not None:
        # rmw_zenoh reports these event types as unsupported, and so does rclpy on it.
        raise UnsupportedEventTypeError("Failed to create event handler: event type is not supported by rmw_zenoh_cpp")
    logger = endpoint._node.get_logger()
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
    handlers: list[EventHandler] = []
    if callback is not None:
        h = EventHandler(callback_group=callback_group, callback=callback)
        h._watch = _IncompatibleQoSWatch(endpoint, h, is_publisher=is_publisher)  # type: ignore[attr-defined]
        handlers.append(h)
    if cbs.matched is not None:
        h = EventHandler(callback_group=callback_group, callback=cbs.matched)
        h._watch = _MatchedWatch(endpoint, h, is_publisher=is_publisher)  # type: ignore[attr-defined]
        handlers.append(h)
    return handlers
