"""The live half of `foxglove-bridge`: every ROS topic of the graph as a Foxglove channel (`cdr` messages,
`ros2msg` schema), subscribed on the bus only while a Foxglove client watches it, and topics that clients
advertise (clientPublish) published on the bus — how the app drives `cmd_vel`.

Channels follow the graph: a topic gets one when someone publishes it with a type diffctl knows, and
loses it when its last publisher goes. The bridge's own publishers are left out so that what a client
sends is not echoed back to it as a new channel.
"""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import foxglove

from diffctl.bag.msgdefs import ros2msg
from diffctl.errors import DiffctlError
from diffctl.foxglove.services import is_hidden
from diffctl.interfaces import types

if TYPE_CHECKING:
    from diffctl.foxglove.settings import BridgeSettings


@dataclass
class _Topic:
    type: str
    channel: foxglove.Channel
    latched: bool
    watchers: int = 0
    sub: Any = None


class LiveBridge:
    def __init__(self, node: Any, context: foxglove.Context, log: Any, settings: BridgeSettings) -> None:
        """`node`: the bridge node's wire presence; `log`: its logger; `settings`: its parameters' values."""
        self.node = node
        self.context = context
        self.log = log
        self.settings = settings
        self._topics: dict[str, _Topic] = {}
        self._by_channel: dict[int, str] = {}
        self._client_pubs: dict[tuple[int, int], tuple[Any, str, str]] = {}  # → (publisher, type, encoding)
        self._lock = threading.RLock()
        self._wake = threading.Event()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._watch, name="foxglove-graph", daemon=True)
        self.server: Any = None
        self.also_sync: list[Callable[[], None]] = []  # more of the server that follows the graph (services)

    def wake(self) -> None:
        """Have the graph thread look at the graph now (as a graph change does)."""
        self._wake.set()

    def start(self) -> None:
        self._thread.start()
        self.node.graph.add_listener(lambda *_: self._wake.set())
        self._wake.set()

    # ------------------------------------------------------------------ graph → channels
    def _watch(self) -> None:
        while not self._stop.is_set():
            self._wake.wait(1.0)
            self._wake.clear()
            if not self._stop.is_set():
                self.sync()
                for follow in self.also_sync:
                    follow()

    def sync(self) -> None:
        g = self.node.graph
        own = self.node.fqn
        offered: dict[str, tuple[str, bool]] = {}
        wanted = self.settings.topics
        hidden_too = self.settings.include_hidden
        for topic in g.topics():
            if not wanted(topic) or (not hidden_too and is_hidden(topic)):
                continue
            pubs = [e for e in g.publishers(topic) if e.node_fqn != own]
            kinds = {e.type for e in pubs}
            if len(kinds) == 1 and types.exists(next(iter(kinds))):
                offered[topic] = (next(iter(kinds)), any(e.transient_local for e in pubs))
        with self._lock:
            gone = [self._forget(t) for t in list(self._topics)
                    if t not in offered or offered[t][0] != self._topics[t].type]
            for topic, (typename, latched) in offered.items():
                if topic not in self._topics:
                    self._add(topic, typename, latched)
        # Closed outside the lock: the SDK reports the unsubscriptions a close causes through our callbacks.
        for t in gone:
            self._close(t)

    def _add(self, topic: str, typename: str, latched: bool) -> None:
        schema = foxglove.Schema(name=typename, encoding="ros2msg", data=ros2msg(typename).encode())
        ch = foxglove.Channel(topic, schema=schema, message_encoding="cdr", context=self.context)
        self._topics[topic] = _Topic(typename, ch, latched)
        self._by_channel[ch.id()] = topic

    def _forget(self, topic: str) -> _Topic:
        t = self._topics.pop(topic)
        self._by_channel.pop(t.channel.id(), None)
        return t

    @staticmethod
    def _close(t: _Topic) -> None:
        if t.sub is not None:
            t.sub.close()
        t.channel.close()

    # ------------------------------------------------------------------ clients watching
    def on_subscribe(self, channel_id: int) -> None:
        with self._lock:
            topic = self._by_channel.get(channel_id)
            if topic is None:
                return
            t = self._topics[topic]
            t.watchers += 1
            if t.sub is None:
                ch = t.channel
                offers = [e.qos_profile for e in self.node.graph.publishers(topic) if e.type == t.type]
                depth, cut = self.settings.qos_depth([q.depth if q is not None else 0 for q in offers])
                if cut:
                    self.log.warning(f"Limiting history depth for topic '{topic}' to {depth}. You may want to "
                                     "increase the max_qos_depth parameter value.")
                reliable = not self.settings.best_effort_topics(topic) and bool(offers) and all(
                    q is not None and q.reliable for q in offers)
                t.sub = self.node.create_subscription(
                    topic, t.type, lambda data, ch=ch: ch.log(data, log_time=time.time_ns()), raw=True,
                    latched=t.latched, depth=depth, reliable=reliable)
                self.log.info(f'Subscribing to topic "{topic}" ({t.type}) on channel {channel_id} with reliablity '
                              f'"{"reliable" if reliable else "best_effort"}"')

    def on_unsubscribe(self, channel_id: int) -> None:
        with self._lock:
            topic = self._by_channel.get(channel_id)
            if topic is None:
                return
            t = self._topics[topic]
            t.watchers = max(0, t.watchers - 1)
            if t.watchers == 0 and t.sub is not None:
                t.sub.close()
                t.sub = None

    # ------------------------------------------------------------------ clients publishing
    def on_client_advertise(self, client_id: int, channel: Any) -> None:
        encoding = channel.encoding
        try:
            if not self.settings.client_topics(channel.topic):
                raise DiffctlError(f"topic {channel.topic!r} is not in client_topic_whitelist")
            if encoding not in ("cdr", "json"):
                raise DiffctlError(f"encoding {encoding!r} is not published", hint="use cdr or json")
            typename = types.check(channel.schema_name or "")
            pub = self.node.create_publisher(channel.topic, typename)
        except DiffctlError as e:
            self.log.warning(f"client {client_id} advertised {channel.topic}: {e}")
            if self.server is not None:
                self.server.publish_status(f"{channel.topic}: {e}", foxglove.websocket.StatusLevel.Error)
            return
        with self._lock:
            self._client_pubs[(client_id, channel.id)] = (pub, typename, encoding)

    def on_client_unadvertise(self, client_id: int, channel_id: int) -> None:
        with self._lock:
            entry = self._client_pubs.pop((client_id, channel_id), None)
        if entry is not None:
            entry[0].close()

    def on_message_data(self, client_id: int, channel_id: int, data: bytes) -> None:
        with self._lock:
            entry = self._client_pubs.get((client_id, channel_id))
        if entry is None:
            return
        pub, typename, encoding = entry
        try:
            if encoding == "cdr":
                types.deserialize(data, typename)  # malformed CDR never reaches the bus
                pub.publish_raw(bytes(data))
            else:
                pub.publish(types.new(typename, json.loads(data)))
        except (DiffctlError, ValueError) as e:
            self.node.throttled(f"fg{pub.topic}", f"dropped a message from a Foxglove client on {pub.topic}: {e}")

    def close(self) -> None:
        self._stop.set()
        self._wake.set()
        self._thread.join(2.0)
        with self._lock:
            gone = [self._forget(t) for t in list(self._topics)]
            pubs = [pub for pub, _, _ in self._client_pubs.values()]
            self._client_pubs.clear()
        for t in gone:
            self._close(t)
        for pub in pubs:
            pub.close()
