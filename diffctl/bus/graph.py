"""The ROS graph as rmw_zenoh shares it: liveliness tokens of nodes, publishers, subscribers, services.

One `Graph` per process keeps a live cache (a liveliness subscriber with history), so it also forgets
whatever dies: a crashed process's tokens vanish when its session drops. The session's own tokens are not
waited for: their owner tells the graph as it declares and undeclares them (`own`), so a node counts the
endpoints it just made at once, as a DDS participant's graph does.
"""

from __future__ import annotations

import threading
import time
from collections import defaultdict
from collections.abc import Callable
from typing import Any

import zenoh

from diffctl.bus import wire
from diffctl.bus.session import domain_id

Listener = Callable[[str, wire.Entity], None]  # (event "put"|"delete", entity)


class Graph:
    def __init__(self, session: zenoh.Session, domain: int | None = None, own: tuple[str, ...] | None = None
                 ) -> None:
        """`own`: the session's live tokens, when their owner reports its own (`own()`) from now on; a graph
        made without it learns the session's tokens from the router like any other."""
        self._session = session
        self._zid = str(session.zid()) if own is not None else None
        self._domain = domain_id() if domain is None else domain
        self._lock = threading.Lock()
        self._entities: dict[str, wire.Entity] = {}
        for key in own or ():
            ent = wire.parse_token(key)
            if ent is not None:
                self._entities[key] = ent
        self._listeners: list[Listener] = []
        self._ready = threading.Event()
        self._last_event = time.monotonic()
        # Bumped on every change, so a waiter (wait_for) wakes when the graph changes instead of polling it.
        self._generation = 0
        self._changed = threading.Condition(threading.Lock())
        self._sub = session.liveliness().declare_subscriber(
            f"{wire.LV_PREFIX}/{self._domain}/**", self._on_token, history=True
        )
        # History arrives asynchronously; a snapshot query tells when the initial picture is complete.
        self.refresh()

    def _on_token(self, sample: zenoh.Sample) -> None:
        self._last_event = time.monotonic()
        key = str(sample.key_expr)
        ent = wire.parse_token(key)
        if ent is None or ent.zid == self._zid:
            return  # this session's own tokens came through `own` already (a late echo must not revive one)
        if sample.kind == zenoh.SampleKind.DELETE:
            with self._lock:
                self._entities.pop(key, None)
                listeners = list(self._listeners)
            event = "delete"
        else:
            with self._lock:
                self._entities[key] = ent
                listeners = list(self._listeners)
            event = "put"
        self._bump()
        for cb in listeners:
            try:
                cb(event, ent)
            except Exception:
                pass

    def own(self, key: str, alive: bool) -> None:
        """A token of this session declared (`alive`) or undeclared just now."""
        ent = wire.parse_token(key)
        if ent is None:
            return
        with self._lock:
            if alive:
                self._entities[key] = ent
            elif self._entities.pop(key, None) is None:
                return
            listeners = list(self._listeners)
        self._bump()
        for cb in listeners:
            try:
                cb("put" if alive else "delete", ent)
            except Exception:
                pass

    def refresh(self, timeout_s: float = 1.0) -> None:
        """Query current tokens (the router answers for everyone) and merge them into the cache.

        Replies arrive on a callback and the wait has a wall-clock bound: with many processes starting at once
        a blocking reply iterator was seen never to end (the query's final reply lost), hanging the caller."""
        done = threading.Event()

        def on_reply(r: Any) -> None:
            if r.ok is None:
                return
            key = str(r.ok.key_expr)
            ent = wire.parse_token(key)
            if ent is not None and ent.zid != self._zid:
                with self._lock:
                    self._entities.setdefault(key, ent)

        try:
            self._session.liveliness().get(
                f"{wire.LV_PREFIX}/{self._domain}/**",
                handler=zenoh.handlers.Callback(on_reply, done.set),
                timeout=timeout_s,
            )
            done.wait(timeout_s + 0.5)
        except zenoh.ZError:
            pass
        self._ready.set()
        self._bump()

    def _bump(self) -> None:
        with self._changed:
            self._generation += 1
            self._changed.notify_all()

    def wait_for(self, condition: Callable[[], bool], timeout_s: float | None) -> bool:
        """Wait until `condition()` (a question about the graph) holds, re-asking it on each change; False
        after `timeout_s` (None: no limit)."""
        deadline = None if timeout_s is None else time.monotonic() + timeout_s
        while True:
            with self._changed:
                generation = self._generation
            if condition():
                return True
            remaining = None if deadline is None else deadline - time.monotonic()
            if remaining is not None and remaining <= 0:
                return False
            with self._changed:
                if self._generation == generation:
                    self._changed.wait(remaining)

    def settle(self, quiet_s: float = 0.05, max_s: float = 0.4) -> None:
        """Wait until tokens stop arriving for `quiet_s` (at most `max_s`): a one-shot tool's full picture."""
        start = time.monotonic()
        while time.monotonic() - start < max_s:
            if time.monotonic() - self._last_event >= quiet_s and time.monotonic() - start >= quiet_s:
                break
            time.sleep(0.01)
        self.refresh()

    def add_listener(self, cb: Listener) -> None:
        with self._lock:
            self._listeners.append(cb)
            current = list(self._entities.values())
        for ent in current:
            cb("put", ent)

    def entities(self, kind: str | None = None) -> list[wire.Entity]:
        with self._lock:
            ents = list(self._entities.values())
        return [e for e in ents if kind is None or e.kind == kind]

    def nodes(self) -> list[str]:
        return sorted({e.node_fqn for e in self.entities(wire.KIND_NODE)})

    def _by_name(self, kinds: tuple[str, ...]) -> dict[str, list[str]]:
        out: dict[str, set[str]] = defaultdict(set)
        for e in self.entities():
            if e.kind in kinds:
                out[e.topic].add(e.type)
        return {k: sorted(v) for k, v in sorted(out.items())}

    def topics(self) -> dict[str, list[str]]:
        """Topic name → types seen on it (more than one type means a mismatch)."""
        return self._by_name((wire.KIND_PUB, wire.KIND_SUB))

    def services(self) -> dict[str, list[str]]:
        return self._by_name((wire.KIND_SERVICE,))

    def publishers(self, topic: str) -> list[wire.Entity]:
        return [e for e in self.entities(wire.KIND_PUB) if e.topic == topic]

    def subscribers(self, topic: str) -> list[wire.Entity]:
        return [e for e in self.entities(wire.KIND_SUB) if e.topic == topic]

    def servers(self, service: str) -> list[wire.Entity]:
        return [e for e in self.entities(wire.KIND_SERVICE) if e.topic == service]

    def node_entities(self, node_fqn: str) -> list[wire.Entity]:
        return [e for e in self.entities() if e.node_fqn == node_fqn and e.kind != wire.KIND_NODE]

    def close(self) -> None:
        try:
            self._sub.undeclare()
        except Exception:
            pass
