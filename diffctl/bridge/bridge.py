"""The running bridge: per entry, one channel per direction between `gz/<topic>` keys and ROS topics.

Semantics follow ros_gz_bridge's parameter_bridge:
- gz→ROS converts each gz sample and publishes it on the ROS topic; ROS→gz the other way;
- a lazy channel holds its source subscription only while its destination has subscribers (ROS side:
  graph subscribers other than this node; gz side: Zenoh matching of the gz publisher);
- gz→ROS channels of rendered data (images, point clouds) are demand-driven whatever `lazy` says: the
  simulator renders a camera only while its gz topic is matched, so the bridge subscribes to it only while
  someone on the ROS side wants the frames (docs: ARCHITECTURE "Sensors without a GPU");
- a bidirectional entry never echoes what it published itself back to where it came from (gz side: the
  Zenoh locality of the gz endpoints; ROS side: the subscription ignores this process's own publishers);
- each ROS endpoint's QoS is declared as read-only `qos_overrides./<topic>.publisher.*` (deadline, depth,
  durability, history, liveliness, reliability) or `.subscription.*` (history, depth, reliability) parameters,
  so `bridge_params` can make a topic transient local as in ROS.

The forwarding itself is a measured hot path: its ROS endpoints are raw ones on the node's wire presence
(`node.bus_node`), beside the client Node that holds the parameters, logging and services.
"""

from __future__ import annotations

import contextlib
import threading
import time
from typing import Any

import zenoh

from diffctl.bridge.config import BridgeEntry
from diffctl.bus import gz, wire
from diffctl.client import qos as client_qos
from diffctl.client.qos_overriding_options import QoSOverridingOptions, declare_qos_parameters
from diffctl.errors import MessageError
from diffctl.interfaces import types

_Kind = client_qos.QoSPolicyKind
# ros_gz_bridge's factory.hpp: what its publishers and subscriptions let parameters override
PUBLISHER_OVERRIDES = QoSOverridingOptions([_Kind.DEADLINE, _Kind.DEPTH, _Kind.DURABILITY, _Kind.HISTORY,
                                            _Kind.LIVELINESS, _Kind.RELIABILITY])
SUBSCRIPTION_OVERRIDES = QoSOverridingOptions.with_default_policies()


def declared_qos(node: Any, topic: str, entry: BridgeEntry, kind: str) -> wire.QoS:
    """The endpoint's QoS after its overrides, declared on `node` as rclcpp declares them."""
    depth = entry.qos.depth or (entry.publisher_queue if kind == "publisher" else entry.subscriber_queue)
    reliability = client_qos.ReliabilityPolicy.RELIABLE if entry.qos.reliable else \
        client_qos.ReliabilityPolicy.BEST_EFFORT
    profile = client_qos.QoSProfile(depth=depth, reliability=reliability)
    declare_qos_parameters(kind, node, topic, profile,
                           PUBLISHER_OVERRIDES if kind == "publisher" else SUBSCRIPTION_OVERRIDES, rclcpp=True)
    return client_qos.to_wire(profile)


def _stamp_now(msg: Any, now: Any) -> None:
    # override_timestamps_with_wall_time: every header (and each transform's) gets the wall clock.
    if hasattr(msg, "header"):
        msg.header.stamp = now
    for t in getattr(msg, "transforms", ()):
        t.header.stamp = now


def _serialize(msg: Any, ros_type: str) -> bytes:
    try:
        return types.serialize(msg, ros_type)
    except Exception as e:  # rosbags raises struct/overflow/type errors for values its CDR fields cannot hold
        raise MessageError(f"not a valid {ros_type}: {type(e).__name__}: {e}") from None


# gz types the simulator renders on demand: their gz subscription is held only while ROS subscribers exist.
RENDERED_GZ_TYPES = frozenset({"gz.msgs.Image", "gz.msgs.PointCloudPacked"})


class GzToRos:
    """gz/<topic> samples → ROS topic."""

    def __init__(self, bridge: Bridge, entry: BridgeEntry) -> None:
        self.entry = entry
        self.bridge = bridge
        self.node = bridge.wire
        self.count = 0
        self._lock = threading.Lock()
        self._sub: Any = None
        self._token: Any = None
        self._closed = False
        self.on_demand = entry.lazy or entry.gz_type in RENDERED_GZ_TYPES
        topic = bridge.node.resolve_topic_name(entry.ros_topic)
        self.pub = self.node.create_publisher(topic, entry.ros_type,
                                              qos=declared_qos(bridge.node, topic, entry, "publisher"))
        # Nobody subscribed on the ROS side: a sample would be converted and put for no one, so it is only
        # counted (a latched topic keeps every sample for late joiners). Zenoh tells when that changes.
        self._heard = True
        self._matching = None
        if not self.pub.latched:
            self._heard = self.pub.matching
            self._matching = self.pub.on_matching(self._on_matching)

    def _on_matching(self, matching: bool) -> None:
        self._heard = matching

    @property
    def active(self) -> bool:
        return self._sub is not None

    def set_active(self, on: bool) -> None:
        with self._lock:
            if on and self._closed:
                return
            if on and self._sub is None:
                self._sub = self.node.session.declare_subscriber(
                    gz.key(self.entry.gz_topic), self._on_sample, allowed_origin=zenoh.Locality.REMOTE
                )
                # listed by `gz topic -l/-i` while it listens, as gz-transport lists ros_gz_bridge's subscriber
                self._token = gz.announce(self.node.session, "sub", self.entry.gz_topic, self.entry.gz_type)
            elif not on and self._sub is not None:
                for obj in (self._token, self._sub):
                    with contextlib.suppress(zenoh.ZError):
                        obj.undeclare()
                self._sub = self._token = None

    def other_subscribers(self) -> int:
        mine = (self.node.context.zid, str(self.node.node_id))
        return sum(
            1
            for e in self.node.graph.subscribers(self.pub.topic)
            if e.type == self.pub.type and (e.zid, e.node_id) != mine
        )

    def _on_sample(self, sample: zenoh.Sample) -> None:
        e = self.entry
        if self._closed:
            return
        if not self._heard:
            self.count += 1
            return
        try:
            _, fields = gz.decode(sample.payload.to_bytes(), e.gz_type)
            msg = e.pair.convert_to_ros(fields)
            if self.bridge.wall_stamps:
                _stamp_now(msg, types.time_msg(time.time_ns()))
            cdr = _serialize(msg, e.ros_type)
        except MessageError as err:
            self.node.throttled(f"gz{e.gz_topic}", f"dropped a sample on gz {e.gz_topic}: {err}")
            return
        try:
            self.pub.publish_raw(cdr)
        except zenoh.ZError:
            return  # a sample still in flight while the bridge shuts down: its publisher is gone
        self.count += 1

    def close(self) -> None:
        self._closed = True
        self.set_active(False)
        if self._matching is not None:
            with contextlib.suppress(Exception):
                self._matching.undeclare()


class RosToGz:
    """ROS topic → gz/<topic> samples."""

    def __init__(self, bridge: Bridge, entry: BridgeEntry) -> None:
        self.entry = entry
        self.node = bridge.wire
        self.count = 0
        self._lock = threading.Lock()
        self._sub: Any = None
        self._closed = False
        self._topic = bridge.node.resolve_topic_name(entry.ros_topic)
        self._qos = declared_qos(bridge.node, self._topic, entry, "subscription")
        self._gz_key = gz.key(entry.gz_topic)
        self.gz_pub = self.node.session.declare_publisher(self._gz_key, allowed_destination=zenoh.Locality.REMOTE)
        self._token = gz.announce(self.node.session, "pub", entry.gz_topic, entry.gz_type)

    @property
    def active(self) -> bool:
        return self._sub is not None

    @property
    def gz_matching(self) -> bool:
        return bool(self.gz_pub.matching_status.matching)

    def set_active(self, on: bool) -> None:
        with self._lock:
            if on and self._closed:
                return
            if on and self._sub is None:
                self._sub = self.node.create_subscription(
                    self._topic, self.entry.ros_type, self._on_cdr, qos=self._qos, raw=True,
                    ignore_local=True,  # never send our own gz→ROS output back to gz
                )
            elif not on and self._sub is not None:
                self._sub.close()
                self._sub = None

    def _on_cdr(self, cdr: bytes) -> None:
        e = self.entry
        if self._closed:
            return
        try:
            msg = types.deserialize(cdr, e.ros_type)
            payload = gz.encode(e.gz_type, e.pair.convert_to_gz(msg))
        except MessageError as err:
            self.node.throttled(f"ros{e.ros_topic}", f"dropped a message on {e.ros_topic}: {err}")
            return
        try:
            self.gz_pub.put(payload)
        except zenoh.ZError:
            return  # in flight while the bridge shuts down
        self.count += 1

    def close(self) -> None:
        self._closed = True
        self.set_active(False)
        for obj in (self._token, self.gz_pub):
            with contextlib.suppress(zenoh.ZError):
                obj.undeclare()


class Bridge:
    """All channels of a bridge config on one node; `start()` declares them, `close()` removes them."""

    def __init__(self, node: Any, entries: list[BridgeEntry]) -> None:
        """`node`: the client Node (parameters, names); the channels' endpoints go on its wire presence."""
        self.node = node
        self.wire = node.bus_node
        self.entries = entries
        self.wall_stamps = bool(node.get_parameter_or("override_timestamps_with_wall_time").value)
        self.gz_to_ros: list[GzToRos] = []
        self.ros_to_gz: list[RosToGz] = []
        self._listeners: list[Any] = []
        self._closed = False

    def start(self) -> Bridge:
        for e in self.entries:
            if e.direction.to_ros:
                self.gz_to_ros.append(GzToRos(self, e))
            if e.direction.to_gz:
                self.ros_to_gz.append(RosToGz(self, e))
        for ch in self.ros_to_gz:
            if ch.entry.lazy:
                self._listeners.append(
                    ch.gz_pub.declare_matching_listener(lambda st, ch=ch: ch.set_active(bool(st.matching)))
                )
                ch.set_active(ch.gz_matching)
            else:
                ch.set_active(True)
        for ch in self.gz_to_ros:
            if not ch.on_demand:
                ch.set_active(True)
        if any(ch.on_demand for ch in self.gz_to_ros):
            self.wire.graph.add_listener(self._on_graph)
            for ch in self.gz_to_ros:
                if ch.on_demand:
                    ch.set_active(ch.other_subscribers() > 0)
        return self

    def _on_graph(self, event: str, ent: wire.Entity) -> None:
        # The graph keeps its listeners for the process lifetime: a closed bridge ignores them.
        if self._closed or ent.kind != wire.KIND_SUB:
            return
        for ch in self.gz_to_ros:
            if ch.on_demand and ent.topic == ch.pub.topic:
                ch.set_active(ch.other_subscribers() > 0)

    def channels(self) -> list[GzToRos | RosToGz]:
        return [*self.gz_to_ros, *self.ros_to_gz]

    def __rich__(self) -> Any:
        from diffctl.console import table

        rows = []
        for ch in self.channels():
            e = ch.entry
            arrow = "<-" if isinstance(ch, GzToRos) else "->"
            on_demand = isinstance(ch, GzToRos) and ch.on_demand and not e.lazy
            state = ("active" if ch.active else "idle") + (" (lazy)" if e.lazy else " (on demand)" if on_demand else "")
            rows.append((e.ros_topic, e.ros_type, arrow, e.gz_topic, e.gz_type, state, ch.count))
        return table("bridge", ["ROS topic", "ROS type", "", "gz topic", "gz type", "state", "messages"], rows)

    def close(self) -> None:
        self._closed = True
        for lst in self._listeners:
            try:
                lst.undeclare()
            except zenoh.ZError:
                pass
        for ch in self.channels():
            ch.close()
