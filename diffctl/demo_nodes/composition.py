"""ros2/demos' `composition` components as Python classes diffctl's component container loads
(`composition::Talker`, `::Listener`, `::NodeLikeListener`, `::Server`, `::Client`, through the
`rclpy_components` entry points): the same node, topic and service names, QoS depths, periods and log lines
as the Jazzy C++ ones, so the composition tutorial and its launch file run where those are not installed.
Each takes the node options (`cli_args`, `parameter_overrides`, …) as keyword arguments."""

from __future__ import annotations

from typing import Any

from example_interfaces.srv import AddTwoInts
from rclpy.node import Node
from std_msgs.msg import String


class Talker(Node):
    """'Hello World: N' on `chatter` every second, counting from 1."""

    def __init__(self, **options: Any) -> None:
        super().__init__("talker", **options)
        self.count = 0
        self.pub = self.create_publisher(String, "chatter", 10)
        self.timer = self.create_timer(1.0, self.on_timer)

    def on_timer(self) -> None:
        self.count += 1
        msg = String(data=f"Hello World: {self.count}")
        self.get_logger().info(f"Publishing: '{msg.data}'")
        self.pub.publish(msg)


class Listener(Node):
    def __init__(self, **options: Any) -> None:
        super().__init__("listener", **options)
        self.sub = self.create_subscription(String, "chatter", self.heard, 10)

    def heard(self, msg: String) -> None:
        self.get_logger().info(f"I heard: [{msg.data}]")


NodeLikeListener = Listener  # upstream's shows a component that only holds a node: the same node here


class Server(Node):
    def __init__(self, **options: Any) -> None:
        super().__init__("Server", **options)
        self.srv = self.create_service(AddTwoInts, "add_two_ints", self.add)

    def add(self, request: Any, response: Any) -> Any:
        self.get_logger().info(f"Incoming request: [a: {request.a}, b: {request.b}]")
        response.sum = request.a + request.b
        return response


class Client(Node):
    """Every 2 s, once `add_two_ints` is there, asks for 2 + 3."""

    def __init__(self, **options: Any) -> None:
        super().__init__("Client", **options)
        self.client = self.create_client(AddTwoInts, "add_two_ints")
        self.timer = self.create_timer(2.0, self.on_timer)

    def on_timer(self) -> None:
        if not self.client.wait_for_service(timeout_sec=1.0):
            self.get_logger().info("Service not available after waiting")
            return
        future = self.client.call_async(AddTwoInts.Request(a=2, b=3))
        future.add_done_callback(lambda f: self.get_logger().info(f"Got result: [{f.result().sum}]"))
