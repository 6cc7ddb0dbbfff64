"""rclpy.service.Service: requests queued by Zenoh's thread, answered from the executor's callback."""

from __future__ import annotations

import collections
import threading
from collections.abc import Callable
from typing import Any

from diffctl.bus import wire
from diffctl.client import waiting
from diffctl.client.interfaces import cls, deserialize, serialize
from diffctl.client.node_entity import NodeEntity
from diffctl.client.service_introspection import REQUEST_RECEIVED, RESPONSE_SENT, ServiceEvents
from diffctl.client.timer import await_or_execute
from diffctl.errors import MessageError


class Service(NodeEntity):
    def __init__(self, node: Any, srv_type: Any, srv_name: str, callback: Callable[[Any, Any], Any],
                 callback_group: Any, qos_profile: Any) -> None:
        self._node = node
        self._srv_type = srv_type  # or, for a node's built-in services, its name until a request needs it
        self.srv_name = srv_name
        self.callback = callback
        self.callback_group = callback_group
        self.qos_profile = qos_profile
        self._executor_event = False
        self._queue: collections.deque[Any] = collections.deque()
        self._lock = threading.Lock()
        self._bus: Any = None
        self._destroyed = False
        self._events = ServiceEvents(node, srv_type)

    @property
    def srv_type(self) -> Any:
        t = self._srv_type
        if isinstance(t, str):
            t = self._srv_type = cls(t)
        return t

    def configure_introspection(self, clock: Any, service_event_qos_profile: Any,
                                introspection_state: Any) -> None:
        """Publish this service's requests and responses on `<service>/_service_event` (OFF stops it)."""
        self._events.configure(self.service_name, clock, service_event_qos_profile, introspection_state)

    def _on_query(self, query: Any) -> None:
        with self._lock:
            self._queue.append(query)
        waiting.notify()

    def _ready(self) -> bool:
        return bool(self._queue)

    def _take(self) -> Callable[[], Any] | None:
        with self._lock:
            if not self._queue:
                return None
            query = self._queue.popleft()
        payload = query.payload.to_bytes() if query.payload is not None else b""
        try:
            request = deserialize(payload, self.srv_type.Request)
        except MessageError as e:  # the caller's fault: answered with the error, the node goes on
            self._node._bus.throttled(f"badreq{self.service_name}",
                                      f"service {self.service_name}: dropped a malformed request: {e}")
            query.reply_err(f"MessageError: {e}")
            return None
        if self._events._pub is not None:
            self._events.publish(REQUEST_RECEIVED, *_caller(query), request)

        async def _execute() -> None:
            response = await await_or_execute(self.callback, request, self.srv_type.Response())
            self.send_response(response, query)

        return _execute

    def send_response(self, response: Any, header: Any) -> None:
        if not isinstance(response, self.srv_type.Response):
            raise TypeError()
        if self._destroyed:
            return
        self._bus.reply(header, serialize(response))
        if self._events._pub is not None:
            self._events.publish(RESPONSE_SENT, *_caller(header), response)

    @property
    def service_name(self) -> str:
        return self._bus.name if self._bus is not None else self.srv_name

    def destroy(self) -> None:
        self._node.destroy_service(self)

    def _destroy(self) -> None:
        if not self._destroyed:
            self._destroyed = True
            if self._bus is not None:
                self._bus.close()
            self._events.close()


def _caller(query: Any) -> tuple[bytes, int]:
    """The calling client's GID and the request's sequence number, from rmw_zenoh's attachment."""
    try:
        seq, _, gid = wire.unpack_attachment(query.attachment.to_bytes())
    except Exception:  # a request without rmw_zenoh's attachment: nothing to attribute it to
        return bytes(16), 0
    return gid, seq
