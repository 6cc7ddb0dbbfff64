"""twist_stamper and twist_unstamper: cmd_vel_in → cmd_vel_out, adding a header (stamped now, frame_id from
the parameter) or taking it off; depth 10 both ways."""

from __future__ import annotations

from typing import Any

from diffctl.interfaces import get_interface as msg


def stamper(node: Any) -> None:
    frame_id = str(node.declare_parameter("frame_id", "").value)
    stamped = msg("geometry_msgs/msg/TwistStamped")
    pub = node.create_publisher(stamped, "cmd_vel_out", 10)

    def on_twist(m: Any) -> None:
        out = stamped(twist=m)
        out.header.stamp = node.get_clock().now().to_msg()
        out.header.frame_id = frame_id
        pub.publish(out)

    node.create_subscription(msg("geometry_msgs/msg/Twist"), "cmd_vel_in", on_twist, 10)
    print("Started twist_stamper!", flush=True)


def unstamper(node: Any) -> None:
    pub = node.create_publisher(msg("geometry_msgs/msg/Twist"), "cmd_vel_out", 10)
    node.create_subscription(msg("geometry_msgs/msg/TwistStamped"), "cmd_vel_in", lambda m: pub.publish(m.twist),
                             10)
    print("Started twist_unstamper!", flush=True)


def run(name: str) -> int:
    """Run twist_stamper or twist_unstamper with this process's ROS arguments until shut down, saying why as the
    package's own main does."""
    from diffctl.client import component
    from diffctl.client.node import Node

    def make() -> Node:
        node = Node(name)
        (stamper if name == "twist_stamper" else unstamper)(node)
        return node

    def stopped(e: BaseException) -> None:
        why = "keyboard interrupt" if isinstance(e, KeyboardInterrupt) else "external shutdown request"
        print(f"Received {why}!")
        print("Exiting...", flush=True)

    return component.run(make, on_stop=stopped)
