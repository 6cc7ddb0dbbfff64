"""Every node's six parameter services and its `/parameter_events`, as rclcpp's ParameterService offers them.

Handlers run on the session's service executor (never on a control loop); the store's lock is the only
thing they share with the node. Answers follow rclcpp: an undeclared name in get/describe empties the whole
response unless the node allows undeclared parameters, in which case it reads as NOT_SET.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from diffctl.bus import parameter_msgs, wire
from diffctl.bus.parameters import TYPE_CODES, ParameterChange, ParameterDescriptor, type_of

if TYPE_CHECKING:
    from diffctl.bus.endpoints import Publisher, Service
    from diffctl.bus.node import Node

RCL = "rcl_interfaces/srv/"
# rmw_qos_profile_parameters and rmw_qos_profile_parameter_events: reliable, volatile, keep_last 1000.
PARAMETER_QOS = wire.QoS(depth=1000)
EVENTS_TOPIC = "/parameter_events"
SERVICES = {
    "describe_parameters": "DescribeParameters",
    "get_parameters": "GetParameters",
    "get_parameter_types": "GetParameterTypes",
    "list_parameters": "ListParameters",
    "set_parameters": "SetParameters",
    "set_parameters_atomically": "SetParametersAtomically",
}


class ParameterServices:
    def __init__(self, node: Node, *, serve: bool = True) -> None:
        """`serve` False: no services of its own; `handlers` answer requests taken elsewhere."""
        from diffctl.bus.endpoints import Publisher, Service

        self.node = node
        self.store = node.parameters
        self.events: Publisher = Publisher(node, EVENTS_TOPIC, "rcl_interfaces/msg/ParameterEvent", qos=PARAMETER_QOS)
        self.handlers = handlers = {
            "describe_parameters": self.describe_parameters, "get_parameters": self.get_parameters,
            "get_parameter_types": self.get_parameter_types, "list_parameters": self.list_parameters,
            "set_parameters": self.set_parameters, "set_parameters_atomically": self.set_parameters_atomically,
        }
        self.services: dict[str, Service] = {}
        for short, srv in SERVICES.items() if serve else ():
            s = Service(node, f"~/{short}", RCL + srv, handlers[short], qos=PARAMETER_QOS)
            self.services[s.name] = s
        self.store.add_listener(self.publish_event)

    # ------------------------------------------------------------------ events
    def publish_event(self, changes: list[ParameterChange]) -> None:
        def params(kind: str) -> list[dict[str, Any]]:
            return [{"name": c.name, "value": _value_or_unset(c.value)} for c in changes if c.kind == kind]

        from diffctl.bus.session import closing

        if closing() or self.events.closed:
            return  # the process is ending: nobody will see the event, and a warning would only alarm
        try:
            self.events.publish({
                "stamp": _time(self.node.now_ns()), "node": self.node.fqn, "new_parameters": params("new"),
                "changed_parameters": params("changed"), "deleted_parameters": params("deleted"),
            })
        except Exception as e:  # a closed session at shutdown must not fail the set that caused the event
            self.node.log.throttled("paramevents", f"could not publish {EVENTS_TOPIC}: {type(e).__name__}: {e}")

    # ------------------------------------------------------------------ handlers
    def _known(self, names: list[str]) -> bool:
        return self.store.allow_undeclared or all(self.store.has(n) for n in names)

    def get_parameters(self, req: Any) -> dict[str, Any]:
        names = [str(n) for n in req.names]
        if not self._known(names):
            return {"values": []}
        return {"values": [_value_or_unset(self.store.values.get(n)) for n in names]}

    def get_parameter_types(self, req: Any) -> dict[str, Any]:
        names = [str(n) for n in req.names]
        if not self._known(names):
            return {"types": []}
        return {"types": [TYPE_CODES[_type_or_unset(self.store.values.get(n))] for n in names]}

    def describe_parameters(self, req: Any) -> dict[str, Any]:
        names = [str(n) for n in req.names]
        if not self._known(names):
            return {"descriptors": []}
        out = []
        for n in names:
            desc = self.store.descriptor(n) if self.store.has(n) else ParameterDescriptor(type="not_set")
            out.append(parameter_msgs.to_descriptor(n, desc))
        return {"descriptors": out}

    def list_parameters(self, req: Any) -> dict[str, Any]:
        names, prefixes = self.store.list([str(p) for p in req.prefixes], int(req.depth))
        return {"result": {"names": names, "prefixes": prefixes}}

    def set_parameters(self, req: Any) -> dict[str, Any]:
        results = []
        for p in req.parameters:
            why = self.store.set_atomically({str(p.name): parameter_msgs.from_value(p.value)})
            results.append({"successful": why is None, "reason": why or ""})
        return {"results": results}

    def set_parameters_atomically(self, req: Any) -> dict[str, Any]:
        why = self.store.set_atomically({str(p.name): parameter_msgs.from_value(p.value) for p in req.parameters})
        return {"result": {"successful": why is None, "reason": why or ""}}

    def close(self) -> None:
        for s in self.services.values():
            s.close()
        self.services.clear()
        self.events.close()


def _type_or_unset(value: Any) -> str:
    try:
        return type_of(value)
    except ValueError:
        return "not_set"


def _value_or_unset(value: Any) -> dict[str, Any]:
    try:
        return parameter_msgs.to_value(value)
    except ValueError:
        return {"type": 0}


def _time(ns: int) -> dict[str, int]:
    return {"sec": int(ns // 1_000_000_000), "nanosec": int(ns % 1_000_000_000)}
