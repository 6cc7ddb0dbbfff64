"""Publishers, subscriptions, service servers and clients on the rmw_zenoh wire format."""

from __future__ import annotations

import itertools
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import zenoh
from zenoh import ext

from diffctl.bus import wire
from diffctl.bus.session import closing, join_after_close
from diffctl.errors import BusError, MessageError, ServiceTimeout
from diffctl.interfaces import types

if TYPE_CHECKING:
    from diffctl.bus.participant import Participant as Node


def endpoint_qos(latched: bool, depth: int | None, reliable: bool, qos: wire.QoS | None) -> wire.QoS:
    """The endpoint's real profile: `qos` if given, else from the flags (a latched endpoint keeps 1 by default)."""
    if qos is not None:
        return qos
    if depth is None:
        depth = 1 if latched else 10
    return wire.QoS(reliable=reliable, transient_local=latched, depth=depth)


def history_depth(qos: wire.QoS) -> int:
    # KEEP_ALL has no depth; bound the late-joiner cache as rmw_zenoh does its own queues.
    return max(1, qos.depth) if not qos.keep_all else 10_000


class Publisher:
    def __init__(self, node: Node, topic: str, typename: str, *, latched: bool = False, depth: int | None = None,
                 reliable: bool = True, qos: wire.QoS | None = None) -> None:
        self.node = node
        self.topic = node.resolve(topic)
        self.type = types.check_defined(typename)
        self.qos = endpoint_qos(latched, depth, reliable, qos)
        self.latched = self.qos.transient_local
        key = wire.topic_key(node.domain, self.topic, self.type)
        token = node.context.entity_token(node, wire.KIND_PUB, self.topic, self.type, self.qos.token())
        self.token_key = token
        self.gid = wire.gid_of(token)
        if self.latched:
            # TRANSIENT_LOCAL: late joiners get up to `depth` of the newest samples, as from a DDS writer's history.
            self._pub = ext.declare_advanced_publisher(
                node.session, key, cache=ext.CacheConfig(max_samples=history_depth(self.qos)),
                publisher_detection=True,
            )
        else:
            # Not express, as rmw_zenoh declares its publishers: an idle link still sends each sample at once,
            # but under load samples share a batch (one write, one read) instead of one syscall each.
            self._pub = node.session.declare_publisher(key, express=False)
        self._token = node.context.declare_token(token)
        self._seq = itertools.count(1)
        # Hot path: bound once, not looked up per message.
        self._encode: Callable[[Any], bytes] | None = None  # compiled on the first message object published
        self._put = self._pub.put
        self._attach = wire.attachment_packer(self.gid)
        node.context.add_local(self.topic, self.type, wire.KIND_PUB, node)
        node.context.local_gids.add(self.gid)

    closed = False

    def publish(self, msg: Any) -> None:
        if isinstance(msg, dict):
            msg = types.new(self.type, msg)
        encode = self._encode
        if encode is None:
            encode = self._encode = types.encoder(self.type)
        self._put(encode(msg), attachment=self._attach(next(self._seq), time.time_ns()))

    def publish_raw(self, cdr: bytes) -> None:
        self._put(cdr, attachment=self._attach(next(self._seq), time.time_ns()))

    @property
    def subscription_count(self) -> int:
        """ROS subscribers of this topic and type anywhere in the graph."""
        return sum(1 for e in self.node.graph.subscribers(self.topic) if e.type == self.type)

    @property
    def matching(self) -> bool:
        """Whether any Zenoh subscriber currently matches (cheap; used for lazy work such as cameras)."""
        try:
            return bool(self._pub.matching_status.matching)
        except Exception:
            return self.subscription_count > 0

    def on_matching(self, callback: Callable[[bool], None]) -> Any:
        """Call `callback(matching)` whenever the presence of subscribers changes."""
        return self._pub.declare_matching_listener(lambda st: callback(bool(st.matching)))

    def close(self) -> None:
        self.closed = True
        for h in (self._token, self._pub):
            try:
                h.undeclare()
            except Exception:
                pass


@dataclass(frozen=True)
class MessageInfo:
    """rclpy's MessageInfo: what the rmw_zenoh attachment says about a sample."""

    sequence_number: int
    source_timestamp_ns: int
    publisher_gid: bytes


class Subscription:
    def __init__(self, node: Node, topic: str, typename: str, callback: Callable[..., None], *,
                 latched: bool = False, depth: int | None = None, raw: bool = False, ignore_local: bool = False,
                 with_info: bool = False, reliable: bool = True, qos: wire.QoS | None = None,
                 samples: bool = False) -> None:
        """`samples`: the callback gets each zenoh.Sample untouched (payload, attachment and all), for a caller
        that queues them on Zenoh's thread and reads them later on its own (the client library)."""
        self.node = node
        self.topic = node.resolve(topic)
        self.type = types.check_defined(typename) if raw else types.check(typename)
        self.callback = callback
        self.raw = raw
        self.with_info = with_info  # callback(msg, MessageInfo)
        # rclcpp's ignore_local_publications: drop samples from publishers of this process (a bridge must
        # not hear its own output on a bidirectional topic).
        self._ignore_gids = node.context.local_gids if ignore_local else None
        self.qos = endpoint_qos(latched, depth, reliable, qos)
        self._decode = None if raw else types.decoder(self.type)
        key = wire.topic_key(node.domain, self.topic, self.type)
        token = node.context.entity_token(node, wire.KIND_SUB, self.topic, self.type, self.qos.token())
        handler = callback if samples else self._on_sample
        if self.qos.transient_local:
            self._sub = ext.declare_advanced_subscriber(
                node.session, key, handler,
                history=ext.HistoryConfig(detect_late_publishers=True, max_samples=history_depth(self.qos)),
                subscriber_detection=True,
            )
        else:
            self._sub = node.session.declare_subscriber(key, handler)
        self._token = node.context.declare_token(token)
        node.context.add_local(self.topic, self.type, wire.KIND_SUB, node)

    def _on_sample(self, sample: zenoh.Sample) -> None:
        # The per-message path: one attachment read, bytes only when needed, the type's compiled decoder.
        att = sample.attachment
        if att is None:
            # rmw_zenoh drops samples without the attachment too; say so instead of staying silent.
            self.node.throttled(f"noatt{self.topic}",
                                    f"dropped a sample on {self.topic} without rmw_zenoh attachment")
            return
        if self._ignore_gids is not None or self.with_info:
            att_bytes = att.to_bytes()
            if self._ignore_gids is not None and att_bytes[17:] in self._ignore_gids:
                return
        data = sample.payload.to_bytes()
        if self.raw:
            msg: Any = data
        else:
            try:
                msg = self._decode(data)
            except MessageError as e:
                self.node.throttled(f"bad{self.topic}", f"dropped a malformed sample on {self.topic}: {e}")
                return
        try:
            if self.with_info:
                try:
                    seq, ts, gid = wire.unpack_attachment(att_bytes)
                except MessageError:
                    seq, ts, gid = 0, 0, b""
                self.callback(msg, MessageInfo(seq, ts, gid))
            else:
                self.callback(msg)
        except Exception as e:  # a user callback must not kill the transport thread
            self.node.throttled(f"cb{self.topic}", f"callback for {self.topic} raised {type(e).__name__}: {e}",
                                    level="ERROR")

    def close(self) -> None:
        for h in (self._token, self._sub):
            try:
                h.undeclare()
            except Exception:
                pass


class Service:
    def __init__(self, node: Node, name: str, srv_type: str, handler: Callable[[Any], Any], *,
                 qos: wire.QoS | None = None, raw: bool = False) -> None:
        """`raw`: `handler(query)` gets each zenoh Query on Zenoh's thread and answers later with `reply`
        (the client library queues requests for its executor); otherwise `handler(request) -> response`
        runs on the session's service threads."""
        self.node = node
        self.raw = raw
        self.name = node.resolve(name)
        self.type = types.check_service(srv_type)
        self.handler = handler
        self.qos = qos or wire.QoS()  # rmw_qos_profile_services_default: reliable, volatile, keep_last 10
        key = wire.service_key(node.domain, self.name, self.type)
        token = node.context.entity_token(node, wire.KIND_SERVICE, self.name, self.type, self.qos.token())
        self._gid = wire.gid_of(token)
        # Called on Zenoh's own thread (`indirect=False`): `_on_query` only hands the query to the executor, so a
        # service needs no Python thread of its own, which zenoh-python otherwise starts for every callback
        # (a node has 7-25 services, declared at start-up; 0.2 ms and a thread each).
        self._q = node.session.declare_queryable(
            key, zenoh.handlers.Callback(self._on_query, indirect=False), complete=True
        )
        self._token = node.context.declare_token(token)

    def _on_query(self, query: zenoh.Query) -> None:
        if self.raw:
            self.handler(query)
            return
        # Handlers may block (a controller switch waits for the control loop): run them off the zenoh thread.
        self.node.context.executor_submit(self._handle, query)

    def _handle(self, query: zenoh.Query) -> None:
        seq, gid = 0, self._gid
        if query.attachment is not None:
            try:
                seq, _, gid = wire.unpack_attachment(query.attachment.to_bytes())
            except MessageError:
                pass
        try:
            payload = query.payload.to_bytes() if query.payload is not None else b""
            req = types.deserialize(payload, self.type + "_Request")
        except MessageError as e:
            # A malformed request is the caller's fault: answer it, but do not let a flood of them flood the log.
            self.node.throttled(f"badreq{self.name}", f"service {self.name}: dropped a malformed request: {e}")
            query.reply_err(f"MessageError: {e}")
            return
        try:
            resp = self.handler(req)
            if isinstance(resp, dict):
                resp = types.response(self.type, resp)
            data = types.serialize(resp, self.type + "_Response")
        except Exception as e:
            self.node.log.error(f"service {self.name} failed: {type(e).__name__}: {e}")
            query.reply_err(f"{type(e).__name__}: {e}")
            return
        query.reply(query.key_expr, data, attachment=wire.pack_attachment(seq, time.time_ns(), gid))

    def reply(self, query: zenoh.Query, data: bytes) -> None:
        """Answer a query taken in raw mode with a serialized response (the request's id echoed back)."""
        seq, gid = 0, self._gid
        if query.attachment is not None:
            try:
                seq, _, gid = wire.unpack_attachment(query.attachment.to_bytes())
            except MessageError:
                pass
        query.reply(query.key_expr, data, attachment=wire.pack_attachment(seq, time.time_ns(), gid))

    def close(self) -> None:
        for h in (self._token, self._q):
            try:
                h.undeclare()
            except Exception:
                pass


class Client:
    def __init__(self, node: Node, name: str, srv_type: str, *, qos: wire.QoS | None = None) -> None:
        self.node = node
        self.name = node.resolve(name)
        self.type = types.check_service(srv_type)
        self.qos = qos or wire.QoS()
        self._key = wire.service_key(node.domain, self.name, self.type)
        token = node.context.entity_token(node, wire.KIND_CLIENT, self.name, self.type, self.qos.token())
        self._gid = wire.gid_of(token)
        self._token = node.context.declare_token(token)
        self._seq = itertools.count(1)
        self._lock = threading.Lock()

    def service_is_ready(self) -> bool:
        return any(e.type == self.type for e in self.node.graph.servers(self.name))

    def wait_for_service(self, timeout: float | None = 5.0) -> bool:
        return self.node.graph.wait_for(self.service_is_ready, timeout)

    def call(self, request: Any = None, timeout: float = 5.0) -> Any:
        if request is None or isinstance(request, dict):
            request = types.request(self.type, request or {})
        data = types.serialize(request, self.type + "_Request")
        with self._lock:
            seq = next(self._seq)
        start = time.monotonic()
        deadline = start + timeout
        attachment = wire.pack_attachment(seq, time.time_ns(), self._gid)
        while True:
            replies = self.node.session.get(
                self._key, payload=data, attachment=attachment, target=zenoh.QueryTarget.ALL_COMPLETE,
                consolidation=zenoh.ConsolidationMode.NONE, timeout=max(0.01, deadline - time.monotonic()),
            )
            for r in replies:
                if r.ok is not None:
                    return types.deserialize(r.ok.payload.to_bytes(), self.type + "_Response")
                err = r.err.payload.to_string()
                if err.strip().lower() == "timeout":  # zenoh's own reply when the deadline passes
                    break
                raise BusError(f"service {self.name} failed: {err}")
            now = time.monotonic()
            if now >= deadline - 0.01:
                raise ServiceTimeout(f"service {self.name} did not answer within {timeout:g} s")
            # No reply at once: nobody serves it, or the server's queryable has not reached our routes yet
            # although its graph token has. Retry while the graph says a server exists (briefly otherwise).
            if not self.service_is_ready() and now - start > 0.5:
                raise BusError(f"no server for service {self.name} ({self.type})",
                               hint="`diffctl service list` shows the services that exist")
            time.sleep(0.02)

    def call_raw_async(self, data: bytes, on_reply: Callable[[bytes | None, str | None], None], *,
                       timeout_s: float = 3600.0) -> int:
        """Send a serialized request; `on_reply(response_bytes, None)` or `on_reply(None, error)` later, on a
        Zenoh thread. A request that found no queryable while the graph shows a server (its route not yet
        propagated) is sent again for up to 10 s (a loaded machine can take seconds); with no server at all it stays
        unanswered, as in ROS."""
        with self._lock:
            seq = next(self._seq)
        attachment = wire.pack_attachment(seq, time.time_ns(), self._gid)
        first = time.monotonic()

        def send() -> None:
            answered = False

            def got(r: Any) -> None:
                nonlocal answered
                if r.ok is not None:
                    answered = True
                    on_reply(r.ok.payload.to_bytes(), None)
                    return
                err = r.err.payload.to_string()
                if err.strip().lower() != "timeout":
                    answered = True
                    on_reply(None, err)

            def done() -> None:
                if answered or self.closed or closing():
                    return
                if time.monotonic() - first < 10.0 and self.service_is_ready():
                    t = threading.Timer(0.02, send)
                    t.daemon = True
                    join_after_close(t)  # it sends on the session: not into the interpreter's finalization
                    t.start()

            try:
                self.node.session.get(
                    self._key, handler=zenoh.handlers.Callback(got, done), payload=data, attachment=attachment,
                    target=zenoh.QueryTarget.ALL_COMPLETE, consolidation=zenoh.ConsolidationMode.NONE,
                    timeout=timeout_s,
                )
            except zenoh.ZError as e:
                on_reply(None, str(e))

        send()
        return seq

    closed = False

    def close(self) -> None:
        self.closed = True
        try:
            self._token.undeclare()
        except Exception:
            pass
