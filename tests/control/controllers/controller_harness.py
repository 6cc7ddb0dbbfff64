"""Drive controller objects directly, without a manager: each on a real client Node (a real router, the
client's parameters, publishers and subscriptions), its clock on sim time set by the test, its log records
and the bytes its realtime publishers hand to the publishing thread recorded (decoded by the client's codec),
and real interface handles.

`client_bus` (tests/control/conftest.py) must be active: the router and the client context of the module.
"""

from __future__ import annotations

from typing import Any

from diffctl.client.clock_type import ClockType
from diffctl.client.duration import Duration
from diffctl.client.interfaces import cls, deserialize
from diffctl.client.parameter import Parameter
from diffctl.client.ros_time import Time
from diffctl.control import realtime_publisher
from diffctl.control.controller_interface import (
    CommandInterface,
    ControllerInterface,
    ControllerInterfaceParams,
    StateInterface,
)
from diffctl.control.lifecycle import State
from diffctl.interfaces.runtime.convert import message_to_ordereddict
from diffctl.interfaces.runtime.set_message import set_message_fields

NS = 1_000_000_000
START_NS = 100 * NS


def _plain(value: Any) -> Any:
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_plain(v) for v in value]
    if hasattr(value, "tolist"):
        return value.tolist()
    return value


class RecordingThread:
    """Stands in for the process's publishing thread: keeps each sample, as the bytes that would be put on the
    wire, decoded back into a dict per topic."""

    _holder = None
    _queue = ()
    dropped = 0

    def __init__(self) -> None:
        self.samples: dict[str, list[dict[str, Any]]] = {}
        self.raw: list[tuple[Any, bytes]] = []

    def submit(self, publisher: Any, template: Any, data: Any) -> None:
        raw = data if template is None else template.encode(data)
        self.raw.append((publisher, raw))
        msg = deserialize(raw, publisher.msg_type)
        self.samples.setdefault(publisher.topic_name, []).append(_plain(message_to_ordereddict(msg)))

    def _wake(self) -> None:
        pass


class RecordingLog:
    def __init__(self) -> None:
        self.lines: list[tuple[str, str]] = []

    def __call__(self, record: Any) -> None:
        level = {10: "DEBUG", 20: "INFO", 30: "WARN", 40: "ERROR", 50: "FATAL"}.get(record.level, str(record.level))
        self.lines.append((level, record.msg))

    def text(self, level: str | None = None) -> str:
        return "\n".join(t for lv, t in self.lines if level is None or lv == level)


class Probe:
    """What a test sees of a controller's node: its clock, what it published, its log, its subscriptions."""

    def __init__(self, node: Any, recorder: RecordingThread) -> None:
        from diffctl.client.ros_logging import attach_rosout

        self.node = node
        self.recorder = recorder
        self.log = RecordingLog()
        attach_rosout(node.get_logger().name, self.log)
        self.time_ns = START_NS

    @property
    def time_ns(self) -> int:
        return self._time_ns

    @time_ns.setter
    def time_ns(self, value: int) -> None:
        self._time_ns = value
        self.node.get_clock().set_ros_time_override(Time(nanoseconds=value, clock_type=ClockType.ROS_TIME))

    def resolve(self, name: str) -> str:
        return self.node.resolve_topic_name(name)

    def sent(self, topic: str) -> list[dict[str, Any]]:
        return self.recorder.samples.get(topic, [])

    @property
    def publishers(self) -> set[str]:
        """The controller's publishers: the node's own /parameter_events (listed, as rclpy lists it) left out."""
        return {p.topic_name for p in self.node.publishers} - {"/parameter_events"}

    @property
    def subscriptions(self) -> dict[str, Any]:
        return {s.topic_name: s for s in self.node.subscriptions}

    def deliver(self, topic: str, values: dict[str, Any]) -> None:
        sub = self.subscriptions[topic]
        msg = sub.msg_type()
        set_message_fields(msg, values)
        sub.callback(msg)

    def parameter(self, name: str) -> Any:
        return self.node.get_parameter(name).value


def make_node(name: str, params: dict[str, Any], namespace: str = "/") -> Any:
    """A controller node as the manager makes one, with `params` as its overrides and the clock on sim time."""
    from diffctl.client.node import Node

    overrides = [Parameter(k, value=v) for k, v in params.items()]
    overrides.append(Parameter("use_sim_time", value=True))
    return Node(name, namespace=namespace, parameter_overrides=overrides, use_global_arguments=False,
                enable_rosout=False, client_library="rclcpp")


def make_controller(cls_: type[ControllerInterface], name: str, params: dict[str, Any], namespace: str = "/",
                    update_rate: int = 100, robot_description: str = "") -> Any:
    """A controller after init (on_init), as the manager leaves it after load_controller; `c.probe` observes it
    (what it publishes is recorded once it is configured through `configure`)."""
    node = make_node(name, params, namespace)
    c = cls_()
    c.probe = Probe(node, RecordingThread())
    c.init(ControllerInterfaceParams(name, robot_description, update_rate, node))
    c._state = State.UNCONFIGURED
    return c


def configure(c: ControllerInterface) -> None:
    realtime_publisher._thread = c.probe.recorder  # the publishers made now hand their samples to it
    c.on_configure(State.UNCONFIGURED)
    c._state = State.INACTIVE
    if c.is_chainable():
        c.export_reference_interfaces()
        c.export_state_interfaces()


def activate(c: ControllerInterface) -> None:
    c.on_activate(State.INACTIVE)
    c._state = State.ACTIVE


def update(c: ControllerInterface, time_ns: int, period_s: float) -> Any:
    return c.update(Time(nanoseconds=time_ns, clock_type=ClockType.ROS_TIME),
                    Duration(nanoseconds=round(period_s * NS)))


def hand_interfaces(
    c: ControllerInterface, values: dict[str, float] | None = None
) -> tuple[dict[str, CommandInterface], dict[str, StateInterface]]:
    """Give the controller the interfaces its configurations name, as the manager does before on_activate;
    returns (command handles, state handles) by name."""
    values = values or {}
    c.command_interfaces = [CommandInterface(n, values.get(n, 0.0)) for n in c.command_interface_configuration().names]
    c.state_interfaces = [StateInterface(n, values.get(n, 0.0)) for n in c.state_interface_configuration().names]
    return {h.name: h for h in c.command_interfaces}, {h.name: h for h in c.state_interfaces}


def message(type_name: str, values: dict[str, Any]) -> Any:
    msg = cls(type_name)()
    set_message_fields(msg, values)
    return msg
