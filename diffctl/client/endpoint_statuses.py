"""What an endpoint feeds its QoS statuses (`qos_status.py`) with: its writes, the samples it receives, the
publishers of its topic coming and going, and liveliness assertions.

A MANUAL_BY_TOPIC publisher's `assert_liveliness()` has no counterpart on rmw_zenoh's wire, so diffctl puts the
publisher's GID on `@diffctl_liveliness/<domain>/<topic>` (a key rmw_zenoh neither writes nor reads); its
samples assert it as well, through the GID of their attachment.
"""

from __future__ import annotations

import time
from typing import Any

from diffctl.bus import wire
from diffctl.client.qos import LivelinessPolicy
from diffctl.client.qos_status import ChangedLiveliness, LostLiveliness, LostMessages, MissedDeadlines


def assertion_key(domain: int, topic: str) -> str:
    return f"@diffctl_liveliness/{domain}/{wire.strip(topic)}"


def _lease_ns(duration: Any) -> int | None:
    ns = duration.nanoseconds
    return ns if 0 < ns < 2**63 - 1 else None


class EndpointStatuses:
    """One endpoint's statuses (those its event handlers asked for) and what feeds them."""

    def __init__(self, qos_profile: Any) -> None:
        self.manual_liveliness = (qos_profile.liveliness == LivelinessPolicy.MANUAL_BY_TOPIC
                                  and _lease_ns(qos_profile.liveliness_lease_duration) is not None)
        self.deadline: MissedDeadlines | None = None
        self.lost: LostLiveliness | None = None
        self.changed: ChangedLiveliness | None = None
        self.lost_messages: LostMessages | None = None
        self._assertions: Any = None  # the Zenoh publisher of a MANUAL_BY_TOPIC publisher's assertions
        self._endpoint: Any = None
        self._writers: _WriterWatch | None = None

    # ------------------------------------------------------------------ a publisher's side
    def write_hook(self, publisher: Any) -> Any:
        """What the publisher calls on each write, or None when nothing needs to know."""
        self._endpoint = publisher
        if self.deadline is None and self.lost is None:
            return None
        return self.wrote

    def wrote(self) -> None:
        now = time.monotonic_ns()
        if self.deadline is not None:
            self.deadline.hit(now)
        if self.lost is not None:
            self.lost.assert_alive(now)

    def assert_liveliness(self, publisher: Any) -> None:
        if self.lost is not None:
            self.lost.assert_alive(time.monotonic_ns())
        if self.manual_liveliness:
            if self._assertions is None:
                bus = publisher._bus.node
                self._assertions = bus.session.declare_publisher(assertion_key(bus.domain, publisher._bus_topic))
            self._assertions.put(publisher._bus.gid)

    # ------------------------------------------------------------------ a subscription's side
    def arrival_hook(self) -> Any:
        """What the subscription calls with each sample's (gid, sequence number), or None."""
        if self.deadline is None and self.changed is None and self.lost_messages is None:
            return None
        return self.arrived

    def arrived(self, gid: bytes, seq: int) -> None:
        now = time.monotonic_ns()
        if self.deadline is not None:
            self.deadline.hit(now)
        if self.lost_messages is not None:
            self.lost_messages.arrived(gid, seq)
        if self.changed is not None and not self.changed.asserted(gid, now) and self._writers is not None:
            # the sample came before its publisher's token reached this process's graph
            self._writers.learn(gid)
            self.changed.asserted(gid, now)

    def watch_writers(self, subscription: Any) -> _WriterWatch:
        """Keeps `changed` told of the topic's publishers and of their assertions."""
        assert self.changed is not None
        self._writers = _WriterWatch(subscription, self.changed)
        return self._writers

    def close(self) -> None:
        if self._assertions is not None:
            try:
                self._assertions.undeclare()
            except Exception:
                pass
            self._assertions = None


class _WriterWatch:
    def __init__(self, subscription: Any, changed: ChangedLiveliness) -> None:
        self._sub = subscription
        self._changed = changed
        self._closed = False
        bus = subscription._node._bus
        bus.graph.add_listener(self._on_graph)
        for ent in bus.graph.publishers(subscription._bus_topic):
            self._on_graph("put", ent)
        self._assertions = bus.session.declare_subscriber(
            assertion_key(bus.domain, subscription._bus_topic), self._on_assertion)

    def _on_graph(self, event: str, ent: wire.Entity) -> None:
        if self._closed or ent.kind != wire.KIND_PUB or ent.topic != self._sub._bus_topic:
            return
        if event == "put":
            if ent.type == self._sub._bus.type:
                qos = ent.qos_profile
                if qos is not None:
                    self._changed.writer(ent.gid, qos.liveliness_lease_ns, qos.manual_liveliness)
        else:
            self._changed.gone(ent.gid)

    def learn(self, gid: bytes) -> None:
        for ent in self._sub._node._bus.graph.publishers(self._sub._bus_topic):
            if ent.gid == gid:
                self._on_graph("put", ent)

    def _on_assertion(self, sample: Any) -> None:
        if not self._closed:
            self._changed.asserted(sample.payload.to_bytes(), time.monotonic_ns())

    def close(self) -> None:
        self._closed = True
        try:
            self._assertions.undeclare()
        except Exception:
            pass
