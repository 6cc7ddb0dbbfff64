"""foxglove_bridge's parameters, declared on the bridge's node as the real one declares them (names, types,
descriptions, ranges, all read-only), and what the bridge makes of their values.

Two values differ from upstream's on purpose: `address` defaults to 127.0.0.1 (diffctl serves loopback only)
and a pattern that is not a regular expression is refused at start (exit 2) rather than logged and skipped.
Patterns match a whole name, ignoring case, as the real bridge's ECMAScript patterns do. `use_compression`,
`send_buffer_limit` and `disable_load_message` are declared for `param list`/`describe` only: the Foxglove SDK
server has no compression or byte-counted send buffer, and diffctl has no loaned messages.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from diffctl.errors import ConfigError
from diffctl.foxglove.assets import DEFAULT_ALLOWLIST
from diffctl.foxglove.server import CAPABILITIES, check_capabilities, check_loopback, check_port

DEFAULT_PORT = 8765
DEFAULT_ADDRESS = "127.0.0.1"
_REGEX_LIST = "List of regular expressions (ECMAScript) of whitelisted {} names."
_INT32_MAX = 2**31 - 1
_INT64_MAX = 2**63 - 1

# name → (default, ParameterType, description, additional_constraints, integer range (from, to, step) or None)
_BOOL, _INTEGER, _STRING, _STRING_ARRAY = 1, 2, 4, 9
DECLARATIONS: dict[str, tuple[Any, int, str, str, tuple[int, int, int] | None]] = {
    "port": (DEFAULT_PORT, _INTEGER, "The TCP port to bind the WebSocket server to",
             "Must be a valid TCP port number, or 0 to use a random port", (0, 65535, 1)),
    "address": (DEFAULT_ADDRESS, _STRING, "The host address to bind the WebSocket server to", "", None),
    "send_buffer_limit": (10_000_000, _INTEGER,
                          "Connection send buffer limit in bytes. Messages will be dropped when a connection's send "
                          "buffer reaches this limit to avoid a queue of outdated messages building up.", "",
                          (0, _INT64_MAX, 0)),
    "tls": (False, _BOOL, "Use Transport Layer Security for encrypted communication", "", None),
    "certfile": ("", _STRING, "Path to the certificate to use for TLS", "", None),
    "keyfile": ("", _STRING, "Path to the private key to use for TLS", "", None),
    "min_qos_depth": (1, _INTEGER, "Minimum depth used for the QoS profile of subscriptions.",
                      "Must be a non-negative integer", (0, _INT32_MAX, 1)),
    "max_qos_depth": (25, _INTEGER, "Maximum depth used for the QoS profile of subscriptions.",
                      "Must be a non-negative integer", (0, _INT32_MAX, 1)),
    "best_effort_qos_topic_whitelist": (
        ["(?!)"], _STRING_ARRAY,
        "List of regular expressions (ECMAScript) for topics that should be forced to use 'best_effort' QoS. "
        "Unmatched topics will use 'reliable' QoS if ALL publishers are 'reliable', 'best_effort' if any "
        "publishers are 'best_effort'.", "", None),
    "topic_whitelist": ([".*"], _STRING_ARRAY, _REGEX_LIST.format("topic"), "", None),
    "service_whitelist": ([".*"], _STRING_ARRAY, _REGEX_LIST.format("service"), "", None),
    "param_whitelist": ([".*"], _STRING_ARRAY, _REGEX_LIST.format("parameter"), "", None),
    "use_compression": (False, _BOOL,
                        "Use websocket compression (permessage-deflate). Suited for connections with smaller "
                        "bandwith, at the cost of additional CPU load.", "", None),
    "capabilities": (list(CAPABILITIES), _STRING_ARRAY, "Server capabilities", "", None),
    # The real bridge hands these two the param_whitelist's descriptor: `describe` shows its description.
    "client_topic_whitelist": ([".*"], _STRING_ARRAY, _REGEX_LIST.format("parameter"), "", None),
    "include_hidden": (False, _BOOL, "Include hidden topics and services", "", None),
    "disable_load_message": (True, _BOOL, "Do not publish as loaned message when publishing a client message", "",
                             None),
    "asset_uri_allowlist": (list(DEFAULT_ALLOWLIST), _STRING_ARRAY, _REGEX_LIST.format("parameter"), "", None),
    "ignore_unresponsive_param_nodes": (True, _BOOL, "Avoid requesting parameters from previously unresponsive nodes",
                                        "", None),
}


class Patterns:
    """A whitelist: a name passes when one pattern matches all of it, case ignored."""

    def __init__(self, field: str, patterns: Sequence[str]) -> None:
        self._res = []
        for p in patterns:
            try:
                self._res.append(re.compile(p, re.IGNORECASE))
            except re.error as e:
                raise ConfigError(f"{p!r} is not a regular expression: {e}", field=field,
                                  hint="a list of regular expressions, each matching a whole name") from None

    def __call__(self, name: str) -> bool:
        return any(r.fullmatch(name) for r in self._res)


@dataclass(frozen=True)
class BridgeSettings:
    port: int
    address: str
    capabilities: frozenset[str]
    topics: Patterns
    services: Patterns
    params: Patterns
    client_topics: Patterns
    best_effort_topics: Patterns
    include_hidden: bool
    ignore_unresponsive_nodes: bool
    min_qos_depth: int
    max_qos_depth: int
    asset_uri_allowlist: tuple[str, ...]
    tls_cert: bytes | None
    tls_key: bytes | None
    use_sim_time: bool

    def qos_depth(self, publisher_depths: Sequence[int]) -> tuple[int, bool]:
        """The bridge's subscription depth for a topic (each publisher's depth, at least 1, summed, then kept
        within min/max_qos_depth) and whether max_qos_depth cut it."""
        depth = max(sum(max(1, d) for d in publisher_depths), self.min_qos_depth)
        return (self.max_qos_depth, True) if depth > self.max_qos_depth else (depth, False)


def declare(node: Any) -> BridgeSettings:
    """Declares every parameter on `node` and reads them back as settings."""
    from diffctl.client.interfaces import cls

    descriptor = cls("rcl_interfaces/msg/ParameterDescriptor")
    integer_range = cls("rcl_interfaces/msg/IntegerRange")
    for name, (default, ptype, description, constraints, bounds) in DECLARATIONS.items():
        d = descriptor(name=name, type=ptype, description=description, additional_constraints=constraints,
                       read_only=True)
        if bounds is not None:
            d.integer_range = [integer_range(from_value=bounds[0], to_value=bounds[1], step=bounds[2])]
        node.declare_parameter(name, default, d)
    values = {name: node.get_parameter(name).value for name in DECLARATIONS}
    return settings_from(values, bool(node.get_parameter("use_sim_time").value))


def settings_from(given: dict[str, Any], use_sim_time: bool = False) -> BridgeSettings:
    """The settings these parameter values make (the defaults for those not given); a value the bridge
    cannot serve with is one ConfigError naming the parameter. The CLI calls it before the node exists too,
    so bad input stops the bridge before it joins the graph."""
    value = {name: decl[0] for name, decl in DECLARATIONS.items()} | given
    cert = key = None
    if value["tls"] is True:
        cert, key = (_read(field, value[field]) for field in ("certfile", "keyfile"))
    try:
        depths = int(value["min_qos_depth"]), int(value["max_qos_depth"])
    except (TypeError, ValueError):
        raise ConfigError(f"min_qos_depth/max_qos_depth: {value['min_qos_depth']!r}/{value['max_qos_depth']!r} "
                          "are not integers", hint="non-negative integers") from None
    return BridgeSettings(
        port=check_port(value["port"]), address=check_loopback(str(value["address"])),
        capabilities=frozenset(check_capabilities(_strings("capabilities", value["capabilities"]))),
        topics=Patterns("topic_whitelist", _strings("topic_whitelist", value["topic_whitelist"])),
        services=Patterns("service_whitelist", _strings("service_whitelist", value["service_whitelist"])),
        params=Patterns("param_whitelist", _strings("param_whitelist", value["param_whitelist"])),
        client_topics=Patterns("client_topic_whitelist",
                               _strings("client_topic_whitelist", value["client_topic_whitelist"])),
        best_effort_topics=Patterns("best_effort_qos_topic_whitelist",
                                    _strings("best_effort_qos_topic_whitelist",
                                             value["best_effort_qos_topic_whitelist"])),
        include_hidden=value["include_hidden"] is True,
        ignore_unresponsive_nodes=value["ignore_unresponsive_param_nodes"] is True,
        min_qos_depth=depths[0], max_qos_depth=depths[1],
        asset_uri_allowlist=tuple(_strings("asset_uri_allowlist", value["asset_uri_allowlist"])),
        tls_cert=cert, tls_key=key, use_sim_time=use_sim_time,
    )


def _strings(field: str, value: Any) -> list[str]:
    if isinstance(value, str) or not all(isinstance(v, str) for v in value):
        raise ConfigError(f"{value!r} is not a list of strings", field=field,
                          hint="a string array, e.g. ['.*']")
    return list(value)


def _read(field: str, path: str) -> bytes:
    if not path:
        raise ConfigError(f"tls is true but {field} is empty", field=field,
                          hint="the path of a PEM file: " + ("certificate" if field == "certfile" else "private key"))
    try:
        return Path(path).read_bytes()
    except OSError as e:
        raise ConfigError(f"cannot read {path}: {e.strerror}", field=field) from None
