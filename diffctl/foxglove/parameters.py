"""The parameters capability of `foxglove-bridge`: the nodes' ROS parameters as Foxglove parameters, read,
set and watched through each node's parameter services, as foxglove_bridge's ParameterInterface does.

A Foxglove parameter is named `<node fqn>.<parameter>` (`/controller_manager.update_rate`; the node name
ends at the first dot, since node names have none). Asking for no names lists every parameter of every node
that serves list_parameters and get_parameters (the bridge's own aside). Doubles carry the `float64` type
hint (and double arrays `float64_array`), so 1.0 stays a double when the app sends it back. Watched
parameters are updated from `/parameter_events` (its changed parameters), only while a client watches.
"""

from __future__ import annotations

import threading
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

import foxglove
from foxglove import ParameterType

from diffctl.client.interfaces import cls
from diffctl.client.parameter import Parameter, from_python_value, parameter_value_to_python

if TYPE_CHECKING:
    from diffctl.foxglove.settings import BridgeSettings

RCL = "rcl_interfaces/srv/"
EVENTS = "/parameter_events"
TIMEOUT_S = 5.0


def split_name(full: str) -> tuple[str, str]:
    """'/ns/node.a.b' → ('/ns/node', 'a.b')."""
    node, _, param = full.partition(".")
    return node, param


def to_foxglove(name: str, parameter_value: Any) -> foxglove.Parameter:
    """A foxglove parameter from an rcl_interfaces/msg/ParameterValue."""
    kind = Parameter.Type(parameter_value.type)
    value = parameter_value_to_python(parameter_value)
    if kind is Parameter.Type.NOT_SET:
        return foxglove.Parameter(name)
    if kind is Parameter.Type.DOUBLE:
        return foxglove.Parameter(name, value=float(value), type=ParameterType.Float64)
    if kind is Parameter.Type.DOUBLE_ARRAY:
        return foxglove.Parameter(name, value=[float(v) for v in value], type=ParameterType.Float64Array)
    if kind is Parameter.Type.BYTE_ARRAY:
        return foxglove.Parameter(name, value=b"".join(value), type=ParameterType.ByteArray)
    return foxglove.Parameter(name, value=value)


def from_foxglove(p: foxglove.Parameter) -> Any:
    """The Python value a ROS node gets (None: unset), honouring the float hints."""
    value = p.get_value()
    if p.type == ParameterType.Float64 and isinstance(value, int | float) and not isinstance(value, bool):
        return float(value)
    if p.type == ParameterType.Float64Array and isinstance(value, list):
        return [float(v) for v in value]
    if p.type == ParameterType.ByteArray and isinstance(value, str | bytes):
        return value if isinstance(value, bytes) else value.encode()
    return value


class ParameterBridge:
    def __init__(self, node: Any, log: Any, settings: BridgeSettings) -> None:
        """`node`: the bridge's client Node, spinning on another thread (its service calls block on it)."""
        self.node = node
        self.log = log
        self.settings = settings
        self._unresponsive: set[str] = set()  # nodes left out of "every parameter" (ignore_unresponsive_…)
        self.server: Any = None
        self._clients: dict[tuple[str, str], Any] = {}
        self._watched: set[str] = set()
        self._events: Any = None
        self._lock = threading.Lock()

    # ------------------------------------------------------------------ calls to one node
    def _call(self, node_fqn: str, short: str, srv: str, **request: Any) -> Any:
        with self._lock:
            client = self._clients.get((node_fqn, short))
            if client is None:
                client = self._clients[(node_fqn, short)] = self.node.create_client(cls(RCL + srv),
                                                                                    f"{node_fqn}/{short}")
        if not client.wait_for_service(TIMEOUT_S):
            raise RuntimeError(f"node {node_fqn} offers no {short} service")
        response = client.call(client.srv_type.Request(**request), timeout_sec=TIMEOUT_S)
        if response is None:
            raise RuntimeError(f"{node_fqn}/{short} did not answer within {TIMEOUT_S:g} s")
        return response

    def _parameter_nodes(self) -> list[str]:
        graph = self.node.bus_node.graph
        services = graph.services()
        return [n for n in graph.nodes() if n != self.node.get_fully_qualified_name() and n not in self._unresponsive
                and RCL + "ListParameters" in services.get(f"{n}/list_parameters", ())
                and RCL + "GetParameters" in services.get(f"{n}/get_parameters", ())]

    # ------------------------------------------------------------------ getParameters / setParameters
    def get(self, names: Iterable[str]) -> list[foxglove.Parameter]:
        wanted: dict[str, list[str]] = {}
        names = list(names)
        if names:
            for full in names:
                node, param = split_name(full)
                wanted.setdefault(node, []).append(param)
        else:
            for node in self._parameter_nodes():
                wanted[node] = []
        out: list[foxglove.Parameter] = []
        for node, params in wanted.items():
            try:
                if not params:
                    params = sorted(str(n) for n in
                                    self._call(node, "list_parameters", "ListParameters").result.names)
                values = self._call(node, "get_parameters", "GetParameters", names=params).values
            except Exception as e:  # one node that does not answer must not hide the others
                self.log.error(f"Failed to retrieve parameters from node '{node}': {e}")
                if self.settings.ignore_unresponsive_nodes:
                    self._unresponsive.add(node)
                    self.log.warning(f"Adding node {node} to the ignore list to prevent repeated timeouts or "
                                     "failures in future parameter requests.")
                continue
            # A node leaves out names it never declared (rclcpp answers them with no values at all).
            pairs = zip(params, values, strict=False)
            out += [to_foxglove(f"{node}.{p}", v) for p, v in pairs]
        return [p for p in out if self.settings.params(p.name)]

    def set(self, parameters: list[foxglove.Parameter]) -> list[foxglove.Parameter]:
        """Set each on its node; returns the values the nodes hold afterwards (a refused one keeps its value)."""
        by_node: dict[str, list[Any]] = {}
        parameters = [p for p in parameters if self.settings.params(p.name)]
        for p in parameters:
            node, param = split_name(p.name)
            by_node.setdefault(node, []).append(from_python_value(param, from_foxglove(p)).to_parameter_msg())
        for node, params in by_node.items():
            try:
                results = self._call(node, "set_parameters", "SetParameters", parameters=params).results
            except Exception as e:
                self._status(f"cannot set parameters of {node}: {e}")
                continue
            for p, r in zip(params, results, strict=False):
                if not r.successful:
                    self._status(f"{node}.{p.name} was not set: {r.reason or 'refused'}")
        return self.get([p.name for p in parameters])

    def _status(self, text: str) -> None:
        self.log.warning(text)
        if self.server is not None:
            self.server.publish_status(text, foxglove.StatusLevel.Warning)

    # ------------------------------------------------------------------ subscribeParameterUpdates
    def subscribe(self, names: list[str]) -> None:
        with self._lock:
            self._watched.update(n for n in names if self.settings.params(n))
            if self._events is None and self._watched:
                self._events = self.node.create_subscription(cls("rcl_interfaces/msg/ParameterEvent"), EVENTS,
                                                             self._on_event, 1000)

    def unsubscribe(self, names: list[str]) -> None:
        with self._lock:
            self._watched.difference_update(names)
            events, self._events = (self._events, None) if not self._watched else (None, self._events)
        if events is not None:
            self.node.destroy_subscription(events)

    def _on_event(self, event: Any) -> None:
        with self._lock:
            changed = [to_foxglove(f"{event.node}.{p.name}", p.value)
                       for p in event.changed_parameters if f"{event.node}.{p.name}" in self._watched]
        if changed and self.server is not None:
            self.server.publish_parameter_values(changed)

    def close(self) -> None:
        with self._lock:
            clients = list(self._clients.values())
            self._clients.clear()
            events, self._events = self._events, None
        if events is not None:
            self.node.destroy_subscription(events)
        for c in clients:
            self.node.destroy_client(c)
