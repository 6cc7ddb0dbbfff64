"""The simulator's side of the bus: gz topics, services and tokens on a Zenoh session, handed to the sim thread.

Publishers know whether anyone listens (a Zenoh matching listener), so the sim skips encoding what nobody
reads and renders cameras only while someone subscribes; samples leave through an `Outbox` thread.
Samples are gz.msgs dicts in the binary encoding of `diffctl.bus.gz` (raw bytes, packed numeric arrays);
a sample that cannot be encoded is dropped with a throttled warning naming the topic, never raised into the
sim loop. Subscription callbacks decode on the Zenoh thread and pass the message to the sim thread through
`Stepper.call_soon`; malformed samples are dropped the same way. Services are queryables whose handler
runs on the sim thread and whose reply is JSON; a handler may also answer later (`Reply.defer`).
"""

from __future__ import annotations

import collections
import json
import threading
from collections.abc import Callable
from typing import Any

import zenoh

from diffctl.bus import gz
from diffctl.errors import DiffctlError, MessageError
from diffctl.sim.log import Logger


class Outbox:
    """Puts samples on a thread of its own, in order. A Zenoh put usually costs microseconds, but when the
    machine is busy its transmit thread falls behind and a put can wait up to a millisecond (measured: 15 µs
    to 0.7 ms on the same run), which the sim thread must not spend, and a full-size camera frame or point
    cloud (1–12 MB) takes longer still. What waits is bounded twice: beyond MAX_BYTES the oldest large samples
    (frames, clouds) are dropped first, so a burst of images never pushes out /clock, IMU or scan samples;
    beyond MAX_QUEUED samples the oldest are dropped, as Zenoh drops for a congested link."""

    MAX_QUEUED = 512
    MAX_BYTES = 48 * 1024 * 1024
    LARGE_BYTES = 64 * 1024
    # More than this waiting when the sim thread ends a batch: the thread is starved, not the network. A sim
    # running flat out (rtf 0) holds the GIL but for the interpreter's forced switches, and a thread that gives
    # the GIL up in every put gets it back only at the next one (5 ms): it moved ~200 samples a second and the
    # rest were dropped. The sim thread then puts the backlog itself.
    INLINE_BACKLOG = 16

    def __init__(self) -> None:
        self._items: collections.deque[tuple[Any, bytes]] = collections.deque()
        self._lock = threading.Lock()
        self._bytes = 0
        self.dropped = 0
        # A binary semaphore, released = "samples may be waiting": a C-level release per wake-up, where an Event's
        # set runs a Condition's Python code (the sim thread pays it at the end of every batch of tasks).
        self._signal = threading.Lock()
        self._signal.acquire()
        # Held from taking a sample to its put's return, by whichever thread puts: samples leave in order.
        self._put_lock = threading.Lock()
        self._stopping = False
        self._holding = False
        self._thread = threading.Thread(target=self._run, name="sim-outbox", daemon=True)
        self._thread.start()

    def put(self, publisher: Any, payload: bytes) -> None:
        with self._lock:
            items = self._items
            items.append((publisher, payload))
            self._bytes += len(payload)
            if self._bytes > self.MAX_BYTES:
                self._drop_large()
            while len(items) > self.MAX_QUEUED:
                self._bytes -= len(items.popleft()[1])
                self.dropped += 1
            first = len(items) == 1
        if first and not self._holding:
            # Only the first of a batch wakes the thread: it drains whatever arrives meanwhile.
            self._wake()

    def hold(self) -> None:
        """Queue without waking the thread until `release` (the sim thread around one step's tasks): each wake
        is an Event.set plus a thread that then asks for the GIL, which ten cars' samples paid one by one."""
        self._holding = True

    def release(self) -> None:
        self._holding = False
        if len(self._items) > self.INLINE_BACKLOG:
            self.drain()
        elif self._items:
            self._wake()

    def _wake(self) -> None:
        # At rtf 0 the thread waits for the GIL long after its wake-up, and nearly every batch finds it signalled
        # already (3,629 of 3,726 wakes in 20 simulated seconds): asked first, that costs no raised exception.
        if not self._signal.locked():
            return
        try:
            self._signal.release()
        except RuntimeError:  # signalled by another producer since the question
            pass

    def drain(self) -> None:
        """Put everything waiting, on the calling thread."""
        while self._put_next():
            pass

    def _drop_large(self) -> None:
        # Oldest large samples first; small ones (clock, IMU, scans) stay. Runs only over budget, under the lock.
        kept: collections.deque[tuple[Any, bytes]] = collections.deque()
        for item in self._items:
            if self._bytes > self.MAX_BYTES and len(item[1]) >= self.LARGE_BYTES:
                self._bytes -= len(item[1])
                self.dropped += 1
            else:
                kept.append(item)
        self._items = kept

    def _next(self) -> tuple[Any, bytes] | None:
        with self._lock:
            if not self._items:
                return None
            item = self._items.popleft()
            self._bytes -= len(item[1])
            return item

    def _put_next(self) -> bool:
        with self._put_lock:
            item = self._next()
            if item is None:
                return False
            try:
                item[0].put(item[1])
            except Exception:
                pass  # undeclared while queued: nobody to deliver to
            return True

    def _run(self) -> None:
        while True:
            self._signal.acquire()
            while self._put_next():
                pass
            if self._stopping:
                return

    def close(self) -> None:
        """Deliver what is queued, then stop."""
        self._stopping = True
        self._wake()
        self._thread.join(2.0)


class GzPublisher:
    def __init__(
        self,
        session: zenoh.Session,
        topic: str,
        gz_type: str,
        outbox: Outbox | None = None,
        log: Logger | None = None,
    ) -> None:
        self.topic = topic
        self._log = log
        self.gz_type = gz_type
        self.key = gz.key(topic)
        self._pub = session.declare_publisher(self.key)
        self._outbox = outbox
        self.matched = bool(self._pub.matching_status.matching)
        self._listener = self._pub.declare_matching_listener(self._on_matching)
        # discoverable by `gz topic -l`, as gz-transport advertises a publisher
        self._token = gz.announce(session, "pub", topic, gz_type)

    def _on_matching(self, status: Any) -> None:
        self.matched = bool(status.matching)

    def publish(self, msg: dict[str, Any]) -> None:
        try:
            payload = gz.encode(self.gz_type, msg)
        except MessageError as e:
            if self._log is None:
                raise
            self._log.throttled(f"enc:{self.topic}", f"dropped a sample on gz topic {self.topic}: {e}")
            return
        self.put_raw(payload)

    def put_raw(self, payload: bytes) -> None:
        if self._outbox is not None:
            self._outbox.put(self._pub, payload)
        else:
            self._pub.put(payload)

    def close(self) -> None:
        for obj in (self._token, self._listener, self._pub):
            try:
                obj.undeclare()
            except Exception:
                pass


class Reply:
    """A pending query answer; `send` it now, or `defer()` and send it later from the sim thread."""

    def __init__(self, query: zenoh.Query) -> None:
        self._query = query
        self.deferred = False

    def defer(self) -> Reply:
        self.deferred = True
        return self

    def send(self, body: dict[str, Any]) -> None:
        try:
            self._query.reply(self._query.key_expr, json.dumps(body, separators=(",", ":")).encode())
        except Exception:
            pass
        finally:
            try:
                self._query.drop()
            except Exception:
                pass


class SimTransport:
    """Everything the sim declares on the bus, closed together."""

    def __init__(self, session: zenoh.Session, call_soon: Callable[[Callable[[], None]], None], log: Logger) -> None:
        self.session = session
        self.call_soon = call_soon
        self.log = log
        self._owned: list[Any] = []
        self.outbox = Outbox()

    def publisher(self, topic: str, gz_type: str) -> GzPublisher:
        p = GzPublisher(self.session, topic, gz_type, self.outbox, self.log)
        self._owned.append(p)
        return p

    def raw_publisher(self, key: str) -> Any:
        p = self.session.declare_publisher(key)
        self._owned.append(p)
        return p

    def subscribe(self, topic: str, gz_type: str, handler: Callable[[dict[str, Any]], None]) -> Any:
        """`handler(fields)` runs on the sim thread for each well-formed sample of `gz_type`."""

        def on_sample(sample: Any) -> None:
            try:
                _, fields = gz.decode(sample.payload.to_bytes(), gz_type)
            except MessageError as e:
                self.log.throttled(f"bad:{topic}", f"dropped a malformed message on gz topic {topic}: {e}")
                return
            self.call_soon(lambda: handler(fields))

        sub = self.session.declare_subscriber(gz.key(topic), on_sample)
        self._owned.append(sub)
        self._owned.append(gz.announce(self.session, "sub", topic, gz_type))
        return sub

    def gz_service(
        self, name: str, request_type: str, response_type: str, handler: Callable[[dict[str, Any]], dict[str, Any]]
    ) -> Any:
        """A gz service (`gz service -s NAME --reqtype … --reptype …`): `handler(request fields)` runs on the sim
        thread and returns the response's fields; a malformed request gets no answer (the caller times out,
        as with gz-transport)."""

        def on_query(query: zenoh.Query) -> None:
            try:
                _, fields = gz.decode(query.payload.to_bytes() if query.payload is not None else b"", request_type)
            except MessageError as e:
                self.log.throttled(f"bad:{name}", f"dropped a malformed request to gz service {name}: {e}")
                query.drop()
                return

            def serve() -> None:
                try:
                    query.reply(query.key_expr, gz.encode(response_type, handler(fields)))
                finally:
                    query.drop()

            self.call_soon(serve)

        q = self.session.declare_queryable(gz.service_key(name), on_query, complete=True)
        both = _Together(q, gz.announce_service(self.session, name, request_type, response_type))
        self._owned.append(both)
        return both

    def raw_subscribe(self, key: str, callback: Callable[[Any], None]) -> Any:
        """A subscriber whose callback runs on the Zenoh thread (for the lockstep path: no hand-over)."""
        sub = self.session.declare_subscriber(key, callback)
        self._owned.append(sub)
        return sub

    def service(
        self,
        key: str,
        handler: Callable[[dict[str, Any], Reply], dict[str, Any] | None],
        fast: Callable[[dict[str, Any]], dict[str, Any] | None] | None = None,
    ) -> Any:
        """A JSON queryable; `handler(request, reply)` runs on the sim thread and returns the answer (or
        defers `reply` and sends it later). Errors become {"ok": false, "error": "..."}. `fast(request)`, when
        given, runs first on the Zenoh thread and may answer at once (e.g. a refusal), without waiting for
        the sim thread, which can be busy in a lockstep wait."""

        def on_query(query: zenoh.Query) -> None:
            raw = query.payload.to_bytes() if query.payload is not None else b""
            try:
                req = json.loads(raw) if raw.strip() else {}
                if not isinstance(req, dict):
                    raise ValueError("the request must be a JSON object")
            except ValueError as e:
                Reply(query).send({"ok": False, "error": f"malformed request: {e}"})
                return
            if fast is not None:
                early = fast(req)
                if early is not None:
                    Reply(query).send(early)
                    return
            self.call_soon(lambda: self._serve(handler, req, Reply(query)))

        q = self.session.declare_queryable(key, on_query, complete=True)
        self._owned.append(q)
        return q

    def direct_service(self, key: str, handler: Callable[[], dict[str, Any]]) -> Any:
        """A JSON queryable answered on the Zenoh thread (for read-only snapshots)."""

        def on_query(query: zenoh.Query) -> None:
            try:
                body = handler()
            except Exception as e:
                body = {"ok": False, "error": f"{type(e).__name__}: {e}"}
            Reply(query).send(body)

        q = self.session.declare_queryable(key, on_query, complete=True)
        self._owned.append(q)
        return q

    def _serve(self, handler: Callable[..., dict[str, Any] | None], req: dict[str, Any], reply: Reply) -> None:
        try:
            body = handler(req, reply)
        except DiffctlError as e:
            body = {"ok": False, "error": str(e)}
        except Exception as e:  # a bug must not kill the sim thread; the caller gets the reason
            self.log.error(f"service failed: {type(e).__name__}: {e}")
            body = {"ok": False, "error": f"{type(e).__name__}: {e}"}
        if not reply.deferred:
            reply.send(body if body is not None else {"ok": True})

    def token(self, key: str) -> Any:
        tok = self.session.liveliness().declare_token(key)
        self._owned.append(tok)
        return tok

    def liveliness_subscriber(self, key: str, callback: Callable[[Any], None]) -> Any:
        sub = self.session.liveliness().declare_subscriber(key, callback, history=True)
        self._owned.append(sub)
        return sub

    def release(self, obj: Any) -> None:
        if obj in self._owned:
            self._owned.remove(obj)
        _undeclare(obj)

    def close(self) -> None:
        self.outbox.close()
        while self._owned:
            _undeclare(self._owned.pop())


class _Together:
    """Declarations released as one (a service's queryable and its announcing token)."""

    def __init__(self, *objs: Any) -> None:
        self._objs = objs

    def undeclare(self) -> None:
        for obj in self._objs:
            _undeclare(obj)


def _undeclare(obj: Any) -> None:
    try:
        if hasattr(obj, "close") and not hasattr(obj, "undeclare"):
            obj.close()
        else:
            obj.undeclare()
    except Exception:
        pass
