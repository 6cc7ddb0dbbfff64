"""Starts the `foxglove-sdk` WebSocket server and routes its callbacks to the live bridge or a bag player.

The server speaks the Foxglove WebSocket protocol (subprotocol `foxglove.sdk.v1`, which the app and
the SDK's servers use) on a loopback address only; each instance has its own SDK context, so channels
never leak between servers in one process (tests run several).
"""

from __future__ import annotations

import ipaddress
from typing import Any

import foxglove
from foxglove.websocket import Capability, ServerListener

from diffctl.errors import ConfigError
from diffctl.foxglove.assets import AssetResolver
from diffctl.foxglove.graph import GraphBridge
from diffctl.foxglove.live import LiveBridge
from diffctl.foxglove.parameters import ParameterBridge
from diffctl.foxglove.playback import BagPlayback
from diffctl.foxglove.services import ServiceBridge

# foxglove_bridge's `capabilities` parameter: its default, and what each name turns on here.
CAPABILITIES = ("clientPublish", "parameters", "parametersSubscribe", "services", "connectionGraph", "assets")


def check_loopback(address: str) -> str:
    try:
        ok = ipaddress.ip_address(address).is_loopback
    except ValueError:
        ok = address == "localhost"
    if not ok:
        raise ConfigError(f"address {address!r} is not a loopback address",
                          hint="diffctl serves Foxglove on 127.0.0.1 or ::1 only")
    return address


def check_port(port: Any) -> int:
    try:
        p = int(port)
    except (TypeError, ValueError):
        p = -1
    if not 0 <= p <= 65535:
        raise ConfigError(f"port {port!r} is not a TCP port", hint="0 to 65535 (0 picks a free one)")
    return p


def check_capabilities(names: list[str]) -> set[str]:
    unknown = [n for n in names if n not in CAPABILITIES]
    if unknown:
        raise ConfigError(f"capabilities: {unknown[0]!r} is not a foxglove_bridge capability",
                          field="capabilities", hint="valid: " + ", ".join(CAPABILITIES))
    return set(names)


class _Listener(ServerListener):
    def __init__(self, live: LiveBridge | None, playback: BagPlayback | None,
                 params: ParameterBridge | None = None, graph: GraphBridge | None = None) -> None:
        self.live = live
        self.playback = playback
        self.params = params
        self.graph = graph

    def on_connection_graph_subscribe(self) -> None:
        if self.graph is not None:
            self.graph.on_subscribe()

    def on_connection_graph_unsubscribe(self) -> None:
        if self.graph is not None:
            self.graph.on_unsubscribe()

    def on_get_parameters(self, client: Any, param_names: list[str], request_id: str | None = None) -> list[Any]:
        return self.params.get(param_names) if self.params is not None else []

    def on_set_parameters(self, client: Any, parameters: list[Any], request_id: str | None = None) -> list[Any]:
        return self.params.set(parameters) if self.params is not None else []

    def on_parameters_subscribe(self, param_names: list[str]) -> None:
        if self.params is not None:
            self.params.subscribe(param_names)

    def on_parameters_unsubscribe(self, param_names: list[str]) -> None:
        if self.params is not None:
            self.params.unsubscribe(param_names)

    def on_subscribe(self, client: Any, channel: Any) -> None:
        if self.live is not None:
            self.live.on_subscribe(channel.id)

    def on_unsubscribe(self, client: Any, channel: Any) -> None:
        if self.live is not None:
            self.live.on_unsubscribe(channel.id)

    def on_client_advertise(self, client: Any, channel: Any) -> None:
        if self.live is not None:
            self.live.on_client_advertise(client.id, channel)

    def on_client_unadvertise(self, client: Any, client_channel_id: int) -> None:
        if self.live is not None:
            self.live.on_client_unadvertise(client.id, client_channel_id)

    def on_message_data(self, client: Any, client_channel_id: int, data: bytes) -> None:
        if self.live is not None:
            self.live.on_message_data(client.id, client_channel_id, data)

    def on_playback_control_request(self, playback_control_request: Any) -> Any:
        if self.playback is None:
            return None
        return self.playback.control(playback_control_request)


def start(host: str, port: int, *, live: LiveBridge | None = None, playback: BagPlayback | None = None,
          context: foxglove.Context, sim_time: bool = False, services: ServiceBridge | None = None,
          params: ParameterBridge | None = None, assets: AssetResolver | None = None,
          client_publish: bool = True, graph: GraphBridge | None = None,
          tls: tuple[bytes, bytes] | None = None) -> Any:
    """The running server (`.port` is the bound port). `sim_time`: the server announces its own time (from
    /clock), as foxglove_bridge does under use_sim_time, so the app's timeline follows the simulation.
    `services`, `params`, `assets`, `graph` (connectionGraph): those capabilities (live graph only). `tls`: the
    certificate and private key (PEM) to serve wss:// with."""
    listener = _Listener(live, playback, params, graph)
    kw: dict[str, Any] = {}
    if playback is not None:
        caps = [Capability.Time]
        kw["playback_time_range"] = playback.time_range
    else:
        caps = [*([Capability.ClientPublish] if live is not None and client_publish else []),
                *([Capability.Time] if sim_time else []),
                *([Capability.Services] if services is not None else []),
                *([Capability.Parameters] if params is not None else []),
                *([Capability.ConnectionGraph] if graph is not None else [])]
        if assets is not None:
            kw["asset_handler"] = assets.fetch  # the SDK then advertises the assets capability
    if tls is not None:
        kw["tls_cert"], kw["tls_key"] = tls
    try:
        server = foxglove.start_server(name="diffctl foxglove_bridge", host=check_loopback(host),
                                       port=check_port(port), capabilities=caps, server_listener=listener,
                                       supported_encodings=["cdr", "json"], context=context, **kw)
    except RuntimeError as e:
        raise ConfigError(f"cannot serve Foxglove on {host}:{port}: {e}", hint="is the port in use? try --port 0") \
            from None
    for part in (live, playback, services, params, graph):
        if part is not None:
            part.server = server
    if services is not None:
        services.sync()
    if live is not None:
        live.also_sync += [part.sync for part in (services, graph) if part is not None]
    return server
