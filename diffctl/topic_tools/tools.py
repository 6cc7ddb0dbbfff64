"""relay, throttle, drop and delay: topic_tools' one-input, one-output nodes, with their parameters and
command lines (`relay <intopic> [outtopic]`, `throttle messages|bytes …`, `drop <intopic> <X> <Y>
[outtopic]`, `delay <intopic> <delay> [outtopic]`), positional arguments taken as parameter overrides."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

from diffctl.errors import ConfigError
from diffctl.topic_tools.gates import ByteThrottle, Drop, MessageThrottle
from diffctl.topic_tools.relay import Relay


def required(node: Any, name: str, type_name: str) -> Any:
    """A statically typed parameter with no default, as `declare_parameter<T>(name)`: it must be given."""
    from diffctl.client.parameter import Parameter

    value = node.declare_parameter(name, getattr(Parameter.Type, type_name)).value
    if value is None:
        raise ConfigError(f"Statically typed parameter '{name}' must be initialized.")
    return value


def _io(node: Any, suffix: str) -> tuple[str, str, bool]:
    input_topic = required(node, "input_topic", "STRING")
    output_topic = node.declare_parameter("output_topic", f"{input_topic}_{suffix}").value
    return input_topic, output_topic, node.declare_parameter("lazy", False).value


def relay(node: Any) -> Relay:
    input_topic, output_topic, lazy = _io(node, "relay")
    holder: list[Relay] = []
    r = Relay(node, input_topic, output_topic, lazy, lambda data: holder[0].publish(data))
    holder.append(r)
    return r


def _wall_ns() -> int:
    return time.monotonic_ns()


def throttle(node: Any) -> Relay | None:
    input_topic, output_topic, lazy = _io(node, "throttle")
    kind = required(node, "throttle_type", "STRING")
    log = node.get_logger()
    if kind == "messages":
        rate = required(node, "msgs_per_sec", "DOUBLE")
        if not rate > 0:
            raise ConfigError(f"parameter 'msgs_per_sec' must be greater than 0, got {rate}")
    elif kind == "bytes":
        bytes_per_sec = required(node, "bytes_per_sec", "INTEGER")
        window_s = required(node, "window", "DOUBLE")
    else:
        log.error("Unknown throttle type")
        return None
    wall = node.declare_parameter("use_wall_clock", False).value
    clock = node.get_clock()
    now: Callable[[], int] = _wall_ns if wall else clock.now_ns
    holder: list[Relay] = []
    if kind == "messages":
        gate = MessageThrottle(rate, now())

        def on_message(data: bytes) -> None:
            admitted = gate.admit(now())
            if gate.jumped_back:
                log.warning("Detected jump back in time, resetting throttle period to now for.")
            if admitted:
                holder[0].publish(data)
    else:
        bytes_gate = ByteThrottle(bytes_per_sec, window_s)

        def on_message(data: bytes) -> None:
            if holder[0].pub is not None and bytes_gate.admit(now(), len(data)):
                holder[0].publish(data)

    holder.append(Relay(node, input_topic, output_topic, lazy, on_message))
    return holder[0]


def drop(node: Any) -> Relay:
    input_topic, output_topic, lazy = _io(node, "drop")
    gate = Drop(required(node, "X", "INTEGER"), required(node, "Y", "INTEGER"))
    holder: list[Relay] = []

    def on_message(data: bytes) -> None:
        if gate.admit():
            holder[0].publish(data)

    holder.append(Relay(node, input_topic, output_topic, lazy, on_message))
    return holder[0]


def delay(node: Any) -> Relay:
    from diffctl.client.clock import Clock

    input_topic = required(node, "input_topic", "STRING")
    output_topic = node.declare_parameter("output_topic", f"{input_topic}_delay").value
    delay_s = node.declare_parameter("delay", 0.0).value
    wall = node.declare_parameter("use_wall_clock", False).value
    holder: list[Relay] = []

    def on_message(data: bytes) -> None:
        def fire() -> None:
            node.destroy_timer(timer)
            holder[0].publish(data)

        timer = node.create_timer(delay_s, fire, clock=Clock() if wall else None)

    holder.append(Relay(node, input_topic, output_topic, False, on_message))
    return holder[0]
