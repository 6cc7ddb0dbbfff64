"""Helpers shared by the bus tools (topic, node, service): YAML values, name lookup, the graph snapshot."""

from __future__ import annotations

import time
from typing import Any

import yaml

from diffctl.bus import wire
from diffctl.bus.graph import Graph
from diffctl.bus.session import open_session, use_client_mode
from diffctl.console import info
from diffctl.errors import ConfigError, MessageError
from diffctl.interfaces import types


def parse_values(text: str | None, what: str = "VALUES") -> dict[str, Any]:
    """ROS-style YAML values (`'{twist: {linear: {x: 0.5}}}'`) → dict, with line/column on errors."""
    if text is None or not text.strip():
        return {}
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as e:
        mark = getattr(e, "problem_mark", None)
        where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark else ""
        raise MessageError(
            f"{what} is not valid YAML{where}: {getattr(e, 'problem', e)}",
            hint="e.g. '{twist: {linear: {x: 0.5}, angular: {z: 0.2}}}'",
        ) from None
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise MessageError(
            f"{what} must be a YAML mapping of fields, got {type(data).__name__} {data!r}", hint="e.g. '{data: hello}'"
        )
    return data


def graph() -> Graph:
    use_client_mode()
    g = Graph(open_session())
    g.settle()
    return g


class ToolNode:
    """A command's own node, as ros2cli makes one: a client Node without parameter services, spinning on a
    thread of its own. One-shot tools use the raw endpoints of its wire presence synchronously; `node` takes
    calls with the client's classes."""

    def __init__(self, name: str, *, use_sim_time: bool = False) -> None:
        from diffctl.client import component
        from diffctl.client.node import Node
        from diffctl.client.parameter import Parameter

        self._started = component.start(
            lambda: Node(
                name,
                start_parameter_services=False,
                parameter_overrides=[Parameter("use_sim_time", value=use_sim_time)],
            )
        )
        self.node = self._started.node
        self.wire = self.node.bus_node
        self.fqn = self.wire.fqn
        self.create_subscription = self.wire.create_subscription
        self.create_publisher = self.wire.create_publisher
        self.create_client = self.wire.create_client

    def now_ns(self) -> int:
        return self.node.get_clock().now().nanoseconds

    def close(self) -> None:
        self._started.stop()


def resolve_name(g: Graph, name: str, names: list[str], what: str = "topic") -> str:
    """An exact name, or the one known name whose last segment matches (`cmd_vel` → `/x/cmd_vel`)."""
    full = "/" + name.lstrip("/")
    if full in names:
        return full
    if "/" not in name.strip("/"):
        matches = sorted(n for n in names if n.rsplit("/", 1)[-1] == name.strip("/"))
        if len(matches) == 1:
            info(f"using {what} {matches[0]} for {name!r}")
            return matches[0]
        if len(matches) > 1:
            raise ConfigError(
                f"{what} {name!r} matches several: {', '.join(matches)}", hint=f"give the full {what} name"
            )
    return full


def topic_types(g: Graph, topic: str) -> list[str]:
    return g.topics().get(topic, [])


def publisher_type(g: Graph, topic: str) -> str | None:
    pubs = g.publishers(topic)
    if pubs:
        return pubs[0].type
    ts = topic_types(g, topic)
    return ts[0] if len(ts) == 1 else None


def wait_for_type(g: Graph, topic: str, typename: str | None, timeout_s: float | None) -> str:
    """The topic's type: given, or learnt from the graph (waiting for a publisher, saying so once). A type
    this process does not know is learnt from a publisher's `~/get_type_description`."""
    t = typename or publisher_type(g, topic)
    if not t:
        info(f"waiting for {topic} to be published…")
        deadline = None if timeout_s is None else time.monotonic() + timeout_s
        while not t:
            time.sleep(0.05)
            t = publisher_type(g, topic)
            if not t and deadline is not None and time.monotonic() > deadline:
                raise ConfigError(
                    f"no publisher on {topic} after {timeout_s:g} s and no TYPE given",
                    hint="pass the type, e.g. geometry_msgs/msg/TwistStamped",
                )
    if not types.exists(t):
        learn_type(g, topic, types.normalize(t))
    return types.check(t)


def learn_type(g: Graph, topic: str, typename: str) -> bool:
    """Register `typename` from the description a publisher of `topic` serves (REP-2016's
    `~/get_type_description`, as `ros2 topic echo` learns types it was not built with); False if none could."""
    from diffctl.bag.msgdefs import register_schema
    from diffctl.interfaces.type_description import SERVICE_TYPE, ros2msg_text

    pubs = [e for e in g.publishers(topic) if types.normalize(e.type) == typename]
    if not pubs:
        return False
    node = ToolNode("diffctl_type_lookup")
    try:
        for e in pubs:
            client = node.create_client(f"{e.node_fqn}/get_type_description", SERVICE_TYPE)
            if not client.wait_for_service(3.0):
                continue
            try:
                resp = client.call({"type_name": typename, "type_hash": e.type_hash}, timeout=5.0)
            except Exception:
                continue
            if not resp.successful:
                continue
            text = ros2msg_text(types.to_dict(resp.type_description))
            register_schema(typename, "ros2msg", text, f"{e.node_fqn}/get_type_description")
            return True
    finally:
        node.close()
    return False


def is_latched(g: Graph, topic: str) -> bool:
    return any(e.transient_local for e in g.publishers(topic))


def sim_time_running(g: Graph) -> bool:
    return bool(g.publishers("/clock"))


def fmt_endpoint(e: wire.Entity) -> str:
    return f"{e.node_fqn} [{e.type}]"
