"""A node's presence on the wire: its liveliness token and the endpoints declared for it.

All nodes of one process share its peer session and a per-session context (entity ids for liveliness
tokens, the graph cache, a small executor for blocking service handlers, type-mismatch reporting). Names
reach this layer fully resolved; naming, parameters, logging and time are the client's Node's business.
"""

from __future__ import annotations

import contextlib
import itertools
import threading
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from typing import Any, Protocol

import zenoh

from diffctl.bus import wire
from diffctl.bus.endpoints import Client, Publisher, Service, Subscription
from diffctl.bus.graph import Graph
from diffctl.bus.session import domain_id, open_session


class Logger(Protocol):
    def warning(self, text: str) -> Any: ...
    def error(self, text: str) -> Any: ...


_contexts: dict[int, _Context] = {}
_contexts_lock = threading.Lock()


class _Context:
    def __init__(self, session: zenoh.Session) -> None:
        self.session = session
        self.zid = str(session.zid())
        self.domain = domain_id()
        self._ids = itertools.count(0)
        self._graph: Graph | None = None
        self._graph_lock = threading.Lock()
        self._executor: ThreadPoolExecutor | None = None
        self._locals: dict[tuple[str, str, str], Participant] = {}  # (topic, type, kind) → a node owning it
        self._warned: set[tuple[str, str, str]] = set()
        self.local_gids: set[bytes] = set()
        self._own_tokens: dict[str, None] = {}  # this session's live graph tokens, known before any echo

    def declare_token(self, key: str) -> OwnToken:
        """A graph token of this session, in this process's graph at once (rclpy counts its own endpoints
        as soon as they are made; the router's echo comes later)."""
        token = self.session.liveliness().declare_token(key)
        with self._graph_lock:
            self._own_tokens[key] = None
            graph = self._graph
        if graph is not None:
            graph.own(key, True)
        return OwnToken(self, key, token)

    def forget_token(self, key: str) -> None:
        with self._graph_lock:
            self._own_tokens.pop(key, None)
            graph = self._graph
        if graph is not None:
            graph.own(key, False)

    def next_id(self) -> int:
        return next(self._ids)

    def entity_token(self, node: Participant, kind: str, topic: str, typename: str, qos: str) -> str:
        return wire.entity_token(self.domain, self.zid, node.node_id, self.next_id(), kind, node.namespace,
                                 node.name, topic, typename, qos)

    @property
    def graph(self) -> Graph:
        with self._graph_lock:
            if self._graph is None:
                self._graph = Graph(self.session, self.domain, own=tuple(self._own_tokens))
                self._graph.add_listener(self._check_mismatch)
            return self._graph

    def add_local(self, topic: str, typename: str, kind: str, node: Participant) -> None:
        self._locals[(topic, typename, kind)] = node
        # Watch the graph so a mismatch is reported, including against endpoints that were already there.
        for ent in self.graph.entities():
            if ent.topic == topic:
                self._check_mismatch("put", ent)

    def _check_mismatch(self, event: str, ent: wire.Entity) -> None:
        if event != "put" or ent.kind not in (wire.KIND_PUB, wire.KIND_SUB):
            return
        for (topic, typename, kind), node in list(self._locals.items()):
            if topic != ent.topic or typename == ent.type:
                continue
            key = (topic, typename, ent.type)
            if key in self._warned:
                continue
            self._warned.add(key)
            mine = "publishes" if kind == wire.KIND_PUB else "subscribes to"
            theirs = "publishes" if ent.kind == wire.KIND_PUB else "subscribes to"
            node.log.warning(
                f"type mismatch on {topic}: this node {mine} {typename} but {ent.node_fqn} {theirs} {ent.type}; "
                "these endpoints will never exchange messages"
            )

    def executor_submit(self, fn: Callable[..., Any], *args: Any) -> None:
        if self._executor is None:
            self._executor = ThreadPoolExecutor(max_workers=4, thread_name_prefix="service")
        self._executor.submit(fn, *args)


class OwnToken:
    """A declared graph token; `undeclare()` takes it out of the graph first, then off the wire."""

    def __init__(self, context: _Context, key: str, token: Any) -> None:
        self._context = context
        self.key = key
        self._token: Any = token

    def undeclare(self) -> None:
        token, self._token = self._token, None
        if token is None:
            return
        self._context.forget_token(self.key)
        token.undeclare()


def _context(session: zenoh.Session) -> _Context:
    with _contexts_lock:
        ctx = _contexts.get(id(session))
        if ctx is None:
            ctx = _contexts[id(session)] = _Context(session)
        return ctx


class Participant:
    """One node on the wire. `log` takes the transport's own warnings (malformed samples, type mismatches)."""

    def __init__(self, name: str, namespace: str, log: Logger, *, session: zenoh.Session | None = None) -> None:
        self.name = name
        self.namespace = namespace
        self.log = log
        self.session = session or open_session()
        self.context = _context(self.session)
        self.domain = self.context.domain
        self.node_id = self.context.next_id()
        self.used_types: dict[str, None] = {}  # every type an endpoint of this node uses (type descriptions)
        self._closables: list[Any] = []
        self._last_warned: dict[str, tuple[float, int]] = {}
        self._token = self.context.declare_token(
            wire.node_token(self.domain, self.context.zid, self.node_id, self.namespace, self.name))

    @property
    def fqn(self) -> str:
        return f"{self.namespace.rstrip('/')}/{self.name}"

    def resolve(self, name: str) -> str:
        """Names reach the wire resolved."""
        return name

    @property
    def graph(self) -> Graph:
        return self.context.graph

    def throttled(self, key: str, text: str, period_s: float = 5.0, level: str = "WARN") -> None:
        """Report at most once per period per key, saying how many were suppressed in between."""
        now = time.monotonic()
        last, suppressed = self._last_warned.get(key, (-period_s, 0))
        if now - last < period_s:
            self._last_warned[key] = (last, suppressed + 1)
            return
        self._last_warned[key] = (now, 0)
        text += f" ({suppressed} more suppressed)" if suppressed else ""
        # two call sites: an rclpy logger fixes each call site's severity on its first call
        if level == "ERROR":
            self.log.error(text)
        else:
            self.log.warning(text)

    # ------------------------------------------------------------------ endpoints
    def _keep(self, obj: Any) -> Any:
        self._closables.append(obj)
        typename = getattr(obj, "type", None)
        if typename is not None:
            self.used_types[typename] = None
        return obj

    def create_publisher(self, topic: str, typename: str, *, latched: bool = False, depth: int | None = None,
                         reliable: bool = True, qos: wire.QoS | None = None) -> Publisher:
        """`latched` is TRANSIENT_LOCAL (depth 1 unless given); `qos` states the whole profile instead."""
        return self._keep(Publisher(self, topic, typename, latched=latched, depth=depth, reliable=reliable, qos=qos))

    def create_subscription(self, topic: str, typename: str, callback: Callable[..., None], *,
                            latched: bool = False, depth: int | None = None, raw: bool = False,
                            ignore_local: bool = False, with_info: bool = False, reliable: bool = True,
                            qos: wire.QoS | None = None, samples: bool = False) -> Subscription:
        """`callback(msg)` (or `callback(bytes)` when raw, `callback(zenoh.Sample)` with `samples`) runs on a Zenoh
        thread: keep it short."""
        return self._keep(Subscription(self, topic, typename, callback, latched=latched, depth=depth, raw=raw,
                                       ignore_local=ignore_local, with_info=with_info, reliable=reliable, qos=qos,
                                       samples=samples))

    def create_service(self, name: str, srv_type: str, handler: Callable[[Any], Any], *,
                       qos: wire.QoS | None = None, raw: bool = False) -> Service:
        return self._keep(Service(self, name, srv_type, handler, qos=qos, raw=raw))

    def create_client(self, name: str, srv_type: str, *, qos: wire.QoS | None = None) -> Client:
        return self._keep(Client(self, name, srv_type, qos=qos))

    def destroy(self, endpoint: Any) -> None:
        """Close an endpoint now and forget it."""
        (endpoint.cancel if hasattr(endpoint, "cancel") else endpoint.close)()
        with contextlib.suppress(ValueError):
            self._closables.remove(endpoint)

    destroy_subscription = destroy

    def close(self) -> None:
        for obj in reversed(self._closables):
            with contextlib.suppress(Exception):
                (obj.cancel if hasattr(obj, "cancel") else obj.close)()
        self._closables.clear()
        with contextlib.suppress(Exception):
            self._token.undeclare()
