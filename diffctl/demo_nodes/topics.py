"""talker and listener: std_msgs/String on `chatter` once a second, in the C++ and the Python flavour; and
demo_nodes_py's talker_qos/listener_qos (sensor-data or reliable QoS, a given number of spin cycles)."""

from __future__ import annotations

import sys
from collections.abc import Callable
from typing import Any

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from std_msgs.msg import String

from diffctl.demo_nodes.spin import spin_node


class Talker(Node):
    """Publishes 'Hello World: N'; `first` and `quote` are where the two upstream talkers differ."""

    def __init__(self, depth: int, first: int, quote: str) -> None:
        super().__init__("talker")
        self.count = first
        self.quote = quote
        self.pub = self.create_publisher(String, "chatter", depth)
        self.timer = self.create_timer(1.0, self.tick)

    def tick(self) -> None:
        msg = String(data=f"Hello World: {self.count}")
        self.count += 1
        self.get_logger().info(f"Publishing: {self.quote}{msg.data}{self.quote}")
        self.pub.publish(msg)


class Listener(Node):
    def __init__(self) -> None:
        super().__init__("listener")
        self.sub = self.create_subscription(String, "chatter", self.heard, 10)

    def heard(self, msg: String) -> None:
        self.get_logger().info(f"I heard: [{msg.data}]")


def _qos_arguments() -> Any:
    """demo_nodes_py's talker_qos/listener_qos options: --reliable, -n/--number_of_cycles (default 20)."""
    import argparse

    from rclpy.utilities import remove_ros_args

    parser = argparse.ArgumentParser(formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--reliable", dest="reliable", action="store_true", help="set qos profile to reliable")
    parser.add_argument("-n", "--number_of_cycles", type=int, default=20, help="number of sending attempts")
    return parser.parse_args(remove_ros_args(args=sys.argv[1:]))


def _qos_profile(reliable: bool) -> Any:
    from rclpy.qos import QoSProfile, QoSReliabilityPolicy, qos_profile_sensor_data

    return QoSProfile(depth=10, reliability=QoSReliabilityPolicy.RELIABLE) if reliable else qos_profile_sensor_data


def _spin_cycles(make: Callable[[], Any], cycles: int) -> int:
    """As demo_nodes_py's QoS nodes: `cycles` spin_once calls (each waits for one callback), then exit 0."""
    rclpy.init()
    node = None
    try:
        node = make()
        for _ in range(cycles):
            if not rclpy.ok():
                break
            rclpy.spin_once(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        if node is not None:
            node.destroy_node()
        rclpy.try_shutdown()
    return 0


class TalkerQos(Node):
    def __init__(self, qos: Any) -> None:
        from rclpy.qos import QoSReliabilityPolicy

        super().__init__("talker_qos")
        self.i = 0
        reliable = qos.reliability is QoSReliabilityPolicy.RELIABLE
        self.get_logger().info("Reliable talker" if reliable else "Best effort talker")
        self.pub = self.create_publisher(String, "chatter", qos)
        self.tmr = self.create_timer(1.0, self.tick)

    def tick(self) -> None:
        msg = String(data=f"Hello World: {self.i}")
        self.i += 1
        self.get_logger().info(f'Publishing: "{msg.data}"')
        self.pub.publish(msg)


class ListenerQos(Node):
    def __init__(self, qos: Any) -> None:
        from rclpy.qos import QoSReliabilityPolicy

        super().__init__("listener_qos")
        reliable = qos.reliability is QoSReliabilityPolicy.RELIABLE
        self.get_logger().info("Reliable listener" if reliable else "Best effort listener")
        self.sub = self.create_subscription(String, "chatter", self.heard, qos)

    def heard(self, msg: String) -> None:
        self.get_logger().info(f"I heard: [{msg.data}]")


def py_talker_qos() -> int:
    args = _qos_arguments()
    return _spin_cycles(lambda: TalkerQos(_qos_profile(args.reliable)), args.number_of_cycles)


def py_listener_qos() -> int:
    args = _qos_arguments()
    return _spin_cycles(lambda: ListenerQos(_qos_profile(args.reliable)), args.number_of_cycles)


def cpp_talker() -> int:
    return spin_node(lambda: Talker(depth=7, first=1, quote="'"))  # rclcpp::KeepLast{7}, size_t count_ = 1


def py_talker() -> int:
    return spin_node(lambda: Talker(depth=10, first=0, quote='"'))


def cpp_listener() -> int:
    return spin_node(Listener)


py_listener = cpp_listener
