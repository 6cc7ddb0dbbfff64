"""The joy_teleop node: its commands built from every parameter it was given, run on each message on `joy`."""

from __future__ import annotations

from typing import Any


def run() -> int:
    from diffctl.client import component
    from diffctl.client.node import Node
    from diffctl.client.qos import QoSDurabilityPolicy, QoSHistoryPolicy, QoSProfile, QoSReliabilityPolicy
    from diffctl.interfaces import get_interface
    from diffctl.joy_teleop.commands import build

    def make() -> Any:
        node = Node("joy_teleop", allow_undeclared_parameters=True,
                    automatically_declare_parameters_from_overrides=True)
        values = {name: p.value for name, p in node.get_parameters_by_prefix("").items()}
        commands = build(node, values)
        qos = QoSProfile(history=QoSHistoryPolicy.KEEP_LAST, depth=1, reliability=QoSReliabilityPolicy.RELIABLE,
                         durability=QoSDurabilityPolicy.VOLATILE)

        def on_joy(msg: Any) -> None:
            for command in commands:
                command.run(msg)

        node.create_subscription(get_interface("sensor_msgs/msg/Joy"), "joy", on_joy, qos)
        return node

    return component.run(make)
