"""Drive controller objects directly: a fake controller node (records what is published, hands out the
subscription callbacks, has a settable clock; its parameters are the bus's real ParameterStore, which does
no I/O) and real interface handles, no manager and no bus."""

from __future__ import annotations

from typing import Any

from diffctl.bus.parameters import ParameterStore
from diffctl.control.controller_interface import CommandInterface, ControllerInterface, StateInterface
from diffctl.interfaces import types

NS = 1_000_000_000


class RecordingLog:
    def __init__(self) -> None:
        self.lines: list[tuple[str, str]] = []

    def debug(self, text: str) -> None:
        self.lines.append(("DEBUG", text))

    def info(self, text: str) -> None:
        self.lines.append(("INFO", text))

    def warn(self, text: str) -> None:
        self.lines.append(("WARN", text))

    def error(self, text: str) -> None:
        self.lines.append(("ERROR", text))

    def text(self, level: str | None = None) -> str:
        return "\n".join(t for lv, t in self.lines if level is None or lv == level)


class FakePublisher:
    """Keeps a dict snapshot of each message: controllers mutate and re-publish one prebuilt message."""

    def __init__(self, topic: str, type_name: str) -> None:
        self.topic, self.type_name = topic, type_name
        self.sent: list[dict[str, Any]] = []
        self.closed = False

    def publish(self, msg: Any) -> None:
        assert msg.__msgtype__ == self.type_name
        types.serialize(msg, self.type_name)  # what the real publisher does: the message must be valid CDR
        self.sent.append(types.to_dict(msg))

    def close(self) -> None:
        self.closed = True


class FakeSubscription:
    def __init__(self, topic: str, type_name: str, callback: Any) -> None:
        self.topic, self.type_name, self.callback = topic, type_name, callback
        self.closed = False

    def close(self) -> None:
        self.closed = True


class FakeNode:
    def __init__(self, name: str, params: dict[str, Any], namespace: str = "/") -> None:
        self.name = name
        self.namespace = namespace
        self.params = params
        self.parameters = ParameterStore(self.params)
        self.log = RecordingLog()
        self.time_ns = 100 * NS
        self.publishers: dict[str, FakePublisher] = {}
        self.subscriptions: dict[str, FakeSubscription] = {}

    def resolve(self, name: str) -> str:
        base = self.namespace.rstrip("/")
        if name.startswith("~"):
            return f"{base}/{self.name}{name[1:]}"
        return name if name.startswith("/") else f"{base}/{name}"

    def create_publisher(self, topic: str, type_name: str, latched: bool = False, depth: int = 10) -> FakePublisher:
        pub = FakePublisher(self.resolve(topic), type_name)
        self.publishers[pub.topic] = pub
        return pub

    def create_subscription(self, topic: str, type_name: str, callback: Any, latched: bool = False) -> Any:
        sub = FakeSubscription(self.resolve(topic), type_name, callback)
        self.subscriptions[sub.topic] = sub
        return sub

    def now_ns(self) -> int:
        return self.time_ns

    def declare_parameter(self, name: str, default: Any, descriptor: Any = None) -> Any:
        return self.parameters.declare(name, default, descriptor)

    def get_parameter(self, name: str) -> Any:
        return self.parameters.get(name)

    def set_parameters(self, values: dict[str, Any]) -> list[str | None]:
        return self.parameters.set(values)

    def add_on_set_parameters_callback(self, cb: Any) -> None:
        self.parameters.add_on_set_callback(cb)

    # --- test helpers ---------------------------------------------------------------------------------------
    def deliver(self, topic: str, values: dict[str, Any]) -> None:
        sub = self.subscriptions[topic]
        sub.callback(types.new(sub.type_name, values))

    def sent(self, topic: str) -> list[dict[str, Any]]:
        pub = self.publishers.get(topic)
        return pub.sent if pub else []


def make_controller(cls: type[ControllerInterface], name: str, params: dict[str, Any], **node_kw: Any) -> Any:
    """A controller after on_init, as the manager leaves it after load_controller."""
    c = cls()
    c.name = name
    c.node = FakeNode(name, params, **node_kw)
    c.on_init()
    return c


def hand_interfaces(
    c: ControllerInterface, values: dict[str, float] | None = None
) -> tuple[dict[str, CommandInterface], dict[str, StateInterface]]:
    """Give the controller the interfaces its configurations name, as the manager does before on_activate;
    returns (command handles, state handles) by name."""
    values = values or {}
    c.command_interfaces = [CommandInterface(n, values.get(n, 0.0)) for n in c.command_interface_configuration().names]
    c.state_interfaces = [StateInterface(n, values.get(n, 0.0)) for n in c.state_interface_configuration().names]
    return {h.name: h for h in c.command_interfaces}, {h.name: h for h in c.state_interfaces}
