"""teleop_twist_joy's teleop_node on the client Node (node name teleop_twist_joy_node): its parameters, as it
declares them and changes them at run time, `joy` in and `cmd_vel` out (depth 10 both)."""

from __future__ import annotations

import math
from typing import Any

from diffctl.teleop_twist_joy.twist_from_joy import ANGULAR, DECLARED, LINEAR, Command, Settings, TeleopTwistJoy

NODE_NAME = "teleop_twist_joy_node"


def declare(node: Any) -> tuple[bool, str, Settings]:
    """(publish_stamped_twist, frame, settings), declared in teleop_node's order with its defaults."""
    values = {name: node.declare_parameter(name, default).value for name, default in DECLARED}
    return bool(values["publish_stamped_twist"]), str(values["frame"]), Settings.from_values(values)


def log_setup(s: Settings) -> None:
    from diffctl.client.ros_logging import get_logger

    log = get_logger("TeleopTwistJoy")
    if s.require_enable_button:
        log.info(f"Teleop enable button {s.enable_button}.")
    if s.enable_turbo_button >= 0:
        log.info(f"Turbo on button {s.enable_turbo_button}.")
    if s.inverted_reverse:
        log.info("Teleop enable inverted reverse.")
    for kind, fields in (("linear", LINEAR), ("angular", ANGULAR)):
        axes, normal, turbo = (s.groups[f"axis_{kind}"], s.groups[f"scale_{kind}"], s.groups[f"scale_{kind}_turbo"])
        for f in sorted(fields):
            if axes[f] != -1:
                log.info(f"{kind.capitalize()} axis {f} on {axes[f]} at scale {normal[f]:f}.")
                if s.enable_turbo_button >= 0:
                    log.info(f"Turbo for {kind} axis {f} is scale {turbo[f]:f}.")


def attach(node: Any) -> TeleopTwistJoy:
    """teleop_node's publisher, subscription and parameter callback on `node`."""
    from diffctl.client.parameter import Parameter
    from diffctl.interfaces import get_interface

    stamped, frame, settings = declare(node)
    log_setup(settings)
    teleop = TeleopTwistJoy(settings)
    twist_cls = get_interface("geometry_msgs/msg/Twist")
    stamped_cls = get_interface("geometry_msgs/msg/TwistStamped")
    vector = get_interface("geometry_msgs/msg/Vector3")
    pub = node.create_publisher(stamped_cls if stamped else twist_cls, "cmd_vel", 10)
    clock, log = node.get_clock(), node.get_logger()

    def send(c: Command) -> None:
        if not all(math.isfinite(v) for v in (*c.linear, *c.angular)):
            log.warning(f"dropped a velocity command that is not finite: {c}", throttle_duration_sec=1.0)
            return
        twist = twist_cls(linear=vector(x=c.linear[0], y=c.linear[1], z=c.linear[2]),
                          angular=vector(x=c.angular[0], y=c.angular[1], z=c.angular[2]))
        if not stamped:
            pub.publish(twist)
            return
        out = stamped_cls(twist=twist)
        out.header.stamp = clock.now().to_msg()
        out.header.frame_id = frame
        pub.publish(out)

    def on_joy(msg: Any) -> None:
        c = teleop.on_joy([float(a) for a in msg.axes], [int(b) for b in msg.buttons])
        if c is not None:
            send(c)

    def on_set(params: list[Parameter]) -> Any:
        # Types are held by the declarations; the new values take effect from the next message.
        for p in params:
            settings.update(p.name, p.value)
        return get_interface("rcl_interfaces/msg/SetParametersResult")(successful=True)

    node.add_on_set_parameters_callback(on_set)
    node.create_subscription(get_interface("sensor_msgs/msg/Joy"), "joy", on_joy, 10)
    return teleop


def run() -> int:
    from diffctl.client import component
    from diffctl.client.node import Node

    def make() -> Any:
        node = Node(NODE_NAME, client_library="rclcpp")
        attach(node)
        return node

    return component.run(make)
