"""A service whose callback answers when it chooses: `handler(request, reply)` with `reply(response)`
callable later, from any thread. rcl_action's servers need it: get_result is answered when the goal ends,
and the goal response goes out before handle_accepted runs."""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from typing import Any

from diffctl.client import qos as _qos
from diffctl.client.interfaces import deserialize, type_name
from diffctl.client.service import Service

Handler = Callable[[Any, Callable[[Any], None]], Awaitable[None]]


class DeferredService(Service):
    def _take(self) -> Callable[[], Any] | None:
        with self._lock:
            if not self._queue:
                return None
            query = self._queue.popleft()
        payload = query.payload.to_bytes() if query.payload is not None else b""
        request = deserialize(payload, self.srv_type.Request)

        async def _execute() -> None:
            await self.callback(request, lambda response: self.send_response(response, query))

        return _execute


def serve(node: Any, srv_type: Any, name: str, handler: Handler, qos_profile: Any, callback_group: Any) -> Service:
    """Declare `name` on `node` as create_service does, with a deferred-answer handler."""
    full = node.resolve_service_name(name)
    service = DeferredService(node, srv_type, name, handler, callback_group, qos_profile)
    service._bus = node.bus_node.create_service(full, type_name(srv_type), service._on_query,
                                                qos=_qos.to_wire(qos_profile), raw=True)
    callback_group.add_entity(service)
    node._services.append(service)
    node._wake_executor()
    return service
