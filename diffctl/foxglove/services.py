"""The services capability of `foxglove-bridge`: every ROS service of the graph advertised to Foxglove clients,
and a client's call made on the bus, as foxglove_bridge does.

A service is advertised with its type as the schema name and the `ros2msg` definitions of `<type>_Request`
and `<type>_Response` (`cdr` encoding); hidden services (a name part starting with `_`) are left out
unless `include_hidden`, and only those `service_whitelist` matches are offered. A
call's CDR goes to the ROS service untouched and the server's CDR comes back as the response; a service that
is gone, a request in another encoding, or no answer within the timeout is a call failure naming why.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import foxglove

from diffctl.bag.msgdefs import ros2msg
from diffctl.errors import DiffctlError
from diffctl.interfaces import types

if TYPE_CHECKING:
    from diffctl.foxglove.settings import BridgeSettings

CALL_TIMEOUT_S = 10.0


def is_hidden(name: str) -> bool:
    """rcl's hidden names: a part that starts with an underscore."""
    return name.startswith("_") or "/_" in name


def service_schema(srv_type: str) -> foxglove.ServiceSchema:
    """The schema foxglove_bridge advertises: request and response definitions as ros2msg, cdr-encoded."""

    def part(suffix: str) -> foxglove.MessageSchema:
        name = srv_type + suffix
        schema = foxglove.Schema(name=name, encoding="ros2msg", data=ros2msg(name).encode())
        return foxglove.MessageSchema(encoding="cdr", schema=schema)

    try:
        return foxglove.ServiceSchema(name=srv_type, request=part("_Request"), response=part("_Response"))
    except (DiffctlError, KeyError, ValueError):
        # A type without a definition here is still callable by a client that knows it (as upstream does).
        return foxglove.ServiceSchema(name=srv_type)


class ServiceBridge:
    """Keeps the server's advertised services equal to the graph's; calls them for clients."""

    def __init__(self, node: Any, log: Any, settings: BridgeSettings) -> None:
        self.node = node
        self.log = log
        self.settings = settings
        self.server: Any = None
        self._advertised: dict[str, str] = {}  # service name → type
        self._clients: dict[str, Any] = {}
        self._lock = threading.Lock()

    def sync(self) -> None:
        if self.server is None:
            return
        wanted, hidden_too = self.settings.services, self.settings.include_hidden
        offered = {name: kinds[0] for name, kinds in self.node.graph.services().items()
                   if kinds and wanted(name) and (hidden_too or not is_hidden(name))}
        with self._lock:
            gone = [n for n, t in self._advertised.items() if offered.get(n) != t]
            for name in gone:
                del self._advertised[name]
                client = self._clients.pop(name, None)
                if client is not None:
                    client.close()
            if gone:
                self.server.remove_services(gone)
            new = [foxglove.Service(name, schema=service_schema(t), handler=self._handler(name, t))
                   for name, t in sorted(offered.items()) if name not in self._advertised]
            if new:
                self.server.add_services(new)
                self._advertised.update({s.name: offered[s.name] for s in new})

    def _handler(self, name: str, srv_type: str) -> Callable[[Any], bytes]:
        def call(request: Any) -> bytes:
            if request.encoding != "cdr":
                raise ValueError(f"service {name} takes cdr requests, not {request.encoding!r}")
            return self.call(name, srv_type, bytes(request.payload))

        return call

    def call(self, name: str, srv_type: str, request_cdr: bytes) -> bytes:
        """One call on the bus; the response's CDR, or an exception whose text the client sees."""
        with self._lock:
            client = self._clients.get(name)
            if client is None:
                client = self._clients[name] = self.node.create_client(name, types.check_service(srv_type))
        if not client.wait_for_service(1.0):
            raise RuntimeError(f"service {name} is not available")
        done = threading.Event()
        result: list[tuple[bytes | None, str | None]] = []

        def on_reply(data: bytes | None, error: str | None) -> None:
            result.append((data, error))
            done.set()

        client.call_raw_async(request_cdr, on_reply, timeout_s=CALL_TIMEOUT_S)
        if not done.wait(CALL_TIMEOUT_S):
            raise TimeoutError(f"service {name} did not answer within {CALL_TIMEOUT_S:g} s")
        data, error = result[0]
        if data is None:
            raise RuntimeError(f"service {name} failed: {error}")
        return data

    def close(self) -> None:
        with self._lock:
            clients = list(self._clients.values())
            self._clients.clear()
        for c in clients:
            c.close()
