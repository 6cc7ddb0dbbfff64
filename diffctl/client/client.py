"""rclpy.client.Client: call_async returns a Future completed by the executor that takes the response."""

from __future__ import annotations

import collections
import threading
import time
from collections.abc import Callable
from typing import Any

from diffctl.client import waiting
from diffctl.client.exceptions import InvalidHandle, RCLError
from diffctl.client.interfaces import deserialize, serialize
from diffctl.client.node_entity import NodeEntity
from diffctl.client.service_introspection import REQUEST_SENT, RESPONSE_RECEIVED, ServiceEvents
from diffctl.client.task import Future


class Client(NodeEntity):
    def __init__(self, node: Any, srv_type: Any, srv_name: str, qos_profile: Any, callback_group: Any) -> None:
        self._node = node
        self.context = node.context
        self.srv_type = srv_type
        self.srv_name = srv_name
        self.qos_profile = qos_profile
        self.callback_group = callback_group
        self._executor_event = False
        self._pending: dict[int, Future] = {}
        self._responses: collections.deque[tuple[int, bytes | None, str | None]] = collections.deque()
        self._lock = threading.Lock()
        self._next = 0
        self._bus: Any = None
        self._destroyed = False
        self._events = ServiceEvents(node, srv_type)

    def configure_introspection(self, clock: Any, service_event_qos_profile: Any,
                                introspection_state: Any) -> None:
        """Publish this client's requests and responses on `<service>/_service_event` (OFF stops it)."""
        self._events.configure(self.service_name, clock, service_event_qos_profile, introspection_state)

    def call_async(self, request: Any) -> Future:
        if self._destroyed:
            raise InvalidHandle("cannot use Destroyable because destruction was requested")
        if not isinstance(request, self.srv_type.Request):
            raise TypeError()
        data = serialize(request)
        future = Future()
        with self._lock:
            self._next += 1
            seq = self._next
            self._pending[seq] = future

        def on_reply(payload: bytes | None, error: str | None) -> None:
            with self._lock:
                self._responses.append((seq, payload, error))
            waiting.notify()

        self._bus.call_raw_async(data, on_reply)
        if self._events._pub is not None:
            # The bus client numbers its requests from 1 as this one does: the same sequence numbers.
            self._events.publish(REQUEST_SENT, self._bus._gid, seq, request)
        return future

    def call(self, request: Any, timeout_sec: float | None = None) -> Any:
        """Block until the response arrives (another thread must be spinning the node); None on timeout."""
        event = threading.Event()
        future = self.call_async(request)
        future.add_done_callback(lambda _f: event.set())
        if not future.done() and not event.wait(timeout_sec):
            self.remove_pending_request(future)
        exc = future.exception()
        if exc is not None:
            raise exc
        return future.result()

    def remove_pending_request(self, future: Future) -> None:
        with self._lock:
            for seq, f in list(self._pending.items()):
                if f is future:
                    del self._pending[seq]

    def _ready(self) -> bool:
        return bool(self._responses)

    def _take(self, executor: Any = None) -> Callable[[], Any] | None:
        with self._lock:
            if not self._responses:
                return None
            seq, payload, _error = self._responses.popleft()
            future = self._pending.pop(seq, None)
        if future is None or payload is None:
            return None  # cancelled or removed meanwhile, or the server failed (rcl never answers then)
        response = deserialize(payload, self.srv_type.Response)
        if self._events._pub is not None:
            self._events.publish(RESPONSE_RECEIVED, self._bus._gid, seq, response)

        async def _execute() -> None:
            if future.cancelled():
                return
            future._set_executor(executor)
            future.set_result(response)

        return _execute

    def service_is_ready(self) -> bool:
        if not self.context._ok:
            raise RCLError("failed to check service availability: rcl node's context is invalid, "
                           "at /project/src/rcl/node.c:404")
        return self._bus.service_is_ready()

    def wait_for_service(self, timeout_sec: float | None = None) -> bool:
        """True once a server of this service and type is in the graph (checked on each graph change)."""
        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        graph = self._node._bus.graph
        while self.context.ok():
            left = None if deadline is None else deadline - time.monotonic()
            if left is not None and left <= 0:
                break
            if graph.wait_for(self.service_is_ready, 0.25 if left is None else min(left, 0.25)):
                return True
        return self.service_is_ready()

    @property
    def service_name(self) -> str:
        """The fully qualified, remapped service name."""
        return self._bus.name

    def destroy(self) -> None:
        self._node.destroy_client(self)

    def _destroy(self) -> None:
        if not self._destroyed:
            self._destroyed = True
            if self._bus is not None:
                self._bus.close()
            self._events.close()
