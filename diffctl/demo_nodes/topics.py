"""talker and listener: std_msgs/String on `chatter` once a second, in the C++ and the Python flavour."""

from __future__ import annotations

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


def cpp_talker() -> int:
    return spin_node(lambda: Talker(depth=7, first=1, quote="'"))  # rclcpp::KeepLast{7}, size_t count_ = 1


def py_talker() -> int:
    return spin_node(lambda: Talker(depth=10, first=0, quote='"'))


def cpp_listener() -> int:
    return spin_node(Listener)


py_listener = cpp_listener
