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
from diffctl.bus.session import domain_id, join_after_close, open_session


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
        self._graph_built: threading.Event | None = None  # set once the graph is made, by whichever thread
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

    def start_graph(self) -> None:
        """Make the graph on a thread of its own, unless it is made or being made: its liveliness subscriber and
        the router's answer to its snapshot query (20-70 ms under load, mostly waiting) then overlap the rest of
        a node's start instead of holding up its first endpoint."""
        with self._graph_lock:
            if self._graph is not None or (self._graph_built is not None and not self._graph_built.is_set()):
                return
            building = self._graph_built = threading.Event()
        maker = threading.Thread(target=self._start_making, args=(building,), name="graph", daemon=True)
        join_after_close(maker)  # a program may end while it is still inside a Zenoh call
        maker.start()

    @property
    def graph(self) -> Graph:
        while True:
            with self._graph_lock:
                if self._graph is not None:
                    return self._graph
                building = self._graph_built
                if building is None or building.is_set():  # none under way, or one that failed: made here
                    building = self._graph_built = threading.Event()
                    mine = True
                else:
                    mine = False
            if mine:
                self._make_graph(building, quiet=False)
            else:
                building.wait()

    def _start_making(self, building: threading.Event) -> None:
        self._make_graph(building, quiet=True)

    def _make_graph(self, building: threading.Event, *, quiet: bool) -> None:
        """Made outside the lock (declaring a token takes it, and must not wait for the router); the tokens
        this session declared or dropped meanwhile are then told to it, and the endpoints of this process
        registered meanwhile are checked against what it found. On a thread of its own (`quiet`), a failure
        (the session closing as the process ends) leaves the graph to be made by the first that needs it."""
        try:
            with self._graph_lock:
                known = dict(self._own_tokens)
            try:
                graph = Graph(self.session, self.domain, own=tuple(known))
            except Exception:
                if quiet:
                    return
                raise
            with self._graph_lock:
                for key in self._own_tokens:
                    if key not in known:
                        graph.own(key, True)
                for key in known:
                    if key not in self._own_tokens:
                        graph.own(key, False)
                self._graph = graph
                graph.add_listener(self._check_mismatch)
                topics = {topic for topic, _, _ in self._locals}
            for ent in graph.entities():
                if ent.topic in topics:
                    self._check_mismatch("put", ent)
        finally:
            building.set()

    def add_local(self, topic: str, typename: str, kind: str, node: Participant) -> None:
        # Watch the graph so a mismatch is reported, including against endpoints that were already there: once
        # it is made, here; while it is being made, where it is made (the registration is seen there or here).
        with self._graph_lock:
            self._locals[(topic, typename, kind)] = node
            graph = self._graph
        if graph is None:
            self.start_graph()
            return
        for ent in graph.entities():
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
        self.context.start_graph()

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
