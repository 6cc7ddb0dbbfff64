"""The twist_mux node: the `topics` and `locks` parameter groups (`<group>.<name>.topic/timeout/priority`,
as its YAML files give them), inputs of geometry_msgs/Twist (or TwistStamped with `use_stamped`), locks of
std_msgs/Bool, the winner republished on `cmd_vel_out`, and /diagnostics every second."""

from __future__ import annotations

from typing import Any

from diffctl.errors import ConfigError
from diffctl.interfaces import get_interface as msg
from diffctl.twist_mux.selection import Handle, lock_priority, winner


def _fetch(node: Any, name: str, kind: type) -> Any:
    if not node.has_parameter(name):
        raise ConfigError(f"could not load parameter '{name}'. (namespace: {node.get_namespace()})")
    value = node.get_parameter(name).value
    if kind is float and isinstance(value, int) and not isinstance(value, bool):
        return float(value)
    if kind is int and isinstance(value, float) and value.is_integer():
        return int(value)
    if not isinstance(value, kind) or isinstance(value, bool):
        raise ConfigError(f"parameter '{name}' must be {'a number' if kind is float else 'an integer'}, "
                          f"got {value!r}")
    return value


def handles(node: Any, group: str) -> list[Handle]:
    """The inputs or locks under `group` ("topics" or "locks"), in name order (rclcpp's parameter map)."""
    prefixes = sorted(node.list_parameters([group], 10).prefixes)
    out = []
    for prefix in prefixes:
        if prefix == group:
            continue
        h = Handle(prefix, _fetch(node, f"{prefix}.topic", str), _fetch(node, f"{prefix}.timeout", float),
                   _fetch(node, f"{prefix}.priority", int))
        node.get_logger().info(
            f"Topic handler '{h.name}' subscribed to topic '{h.topic}': timeout = "
            f"{f'{h.timeout_s:f}s' if h.timeout_s > 0 else 'None'} , priority = {h.priority}.")
        out.append(h)
    return out


class TwistMux:
    def __init__(self, node: Any) -> None:
        from diffctl.client.clock import Clock
        from diffctl.client.qos import QoSProfile, qos_profile_system_default

        self.node, self.clock = node, node.get_clock()
        stamped = node.get_parameter("use_stamped").value if node.has_parameter("use_stamped") else False
        if not isinstance(stamped, bool):
            raise ConfigError(f"parameter 'use_stamped' must be true or false, got {stamped!r}")
        twist = msg("geometry_msgs/msg/TwistStamped" if stamped else "geometry_msgs/msg/Twist")
        self.velocities = handles(node, "topics")
        self.locks = handles(node, "locks")
        self.pub = node.create_publisher(twist, "cmd_vel_out", QoSProfile(depth=1))
        for h in self.velocities:
            node.create_subscription(twist, h.topic, lambda m, h=h: self.on_velocity(h, m),
                                     qos_profile_system_default)
        for h in self.locks:
            node.create_subscription(msg("std_msgs/msg/Bool"), h.topic, lambda m, h=h: self.on_lock(h, m),
                                     qos_profile_system_default)
        self.diag_pub = node.create_publisher(msg("diagnostic_msgs/msg/DiagnosticArray"), "/diagnostics",
                                              QoSProfile(depth=10))
        node.create_timer(1.0, self.publish_diagnostics, clock=Clock())

    def on_velocity(self, h: Handle, m: Any) -> None:
        now = self.clock.now_ns()
        h.stamp_ns, h.message = now, m
        if winner(self.velocities, self.locks, now) == h.name:
            self.pub.publish(m)

    def on_lock(self, h: Handle, m: Any) -> None:
        h.stamp_ns, h.message = self.clock.now_ns(), m

    def publish_diagnostics(self) -> None:
        now = self.clock.now_ns()
        floor = lock_priority(self.locks, now)
        kv = msg("diagnostic_msgs/msg/KeyValue")
        values = [kv(key=f"velocity {h.name}",
                     value=f" {'masked' if h.masked(floor, now) else 'unmasked'} (listening to {h.topic} @ "
                           f"{h.timeout_s:f}s with priority #{h.priority})") for h in self.velocities]
        values += [kv(key=f"lock {h.name}",
                      value=f" {'locked' if h.locked(now) else 'free'} (listening to {h.topic} @ {h.timeout_s:f}s "
                            f"with priority #{h.priority})") for h in self.locks]
        values += [kv(key="current priority", value=str(floor)), kv(key="loop time in [sec]", value="0"),
                   kv(key="data age in [sec]", value="0")]
        status = msg("diagnostic_msgs/msg/DiagnosticStatus")(
            level=b"\x00", name=f"{self.node.get_name()}: Twist mux status", message="ok", hardware_id="none",
            values=values)
        array = msg("diagnostic_msgs/msg/DiagnosticArray")(status=[status])
        array.header.stamp = self.clock.now().to_msg()
        self.diag_pub.publish(array)


def run() -> int:
    """Start twist_mux with this process's ROS arguments; spin until shut down."""
    from diffctl.client import component
    from diffctl.client.node import Node

    def make() -> Node:
        node = Node("twist_mux", allow_undeclared_parameters=True,
                    automatically_declare_parameters_from_overrides=True)
        TwistMux(node)
        return node

    return component.run(make)
