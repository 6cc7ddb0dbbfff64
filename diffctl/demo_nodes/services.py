"""add_two_ints server and client (example_interfaces/srv/AddTwoInts on `add_two_ints`; the client asks 2 + 3)."""

from __future__ import annotations

import rclpy
from example_interfaces.srv import AddTwoInts
from rclpy.node import Node

from diffctl.demo_nodes.spin import spin_node


class Server(Node):
    def __init__(self, one_shot_parameter: bool) -> None:
        super().__init__("add_two_ints_server")
        self.srv = self.create_service(AddTwoInts, "add_two_ints", self.add)
        self.saw_request = False
        # The C++ server's `one_shot` parameter: shut down once a request has been answered.
        if one_shot_parameter and self.declare_parameter("one_shot", False).value:
            self.timer = self.create_timer(0.1, self.stop_after_request)

    def add(self, request: AddTwoInts.Request, response: AddTwoInts.Response) -> AddTwoInts.Response:
        self.get_logger().info(f"Incoming request\na: {request.a} b: {request.b}")
        response.sum = request.a + request.b
        self.saw_request = True
        return response

    def stop_after_request(self) -> None:
        if self.saw_request:
            rclpy.shutdown()


def cpp_server() -> int:
    return spin_node(lambda: Server(one_shot_parameter=True))


def py_server() -> int:
    return spin_node(lambda: Server(one_shot_parameter=False))


def _client(cpp: bool) -> int:
    rclpy.init()
    node = rclpy.create_node("add_two_ints_client")
    try:
        client = node.create_client(AddTwoInts, "add_two_ints")
        while not client.wait_for_service(timeout_sec=1.0):
            if not rclpy.ok():
                node.get_logger().error("Interrupted while waiting for the service. Exiting.")
                return 0
            # rclcpp logs this line, the Python client prints it
            if cpp:
                node.get_logger().info("service not available, waiting again...")
            else:
                print("service not available, waiting again...", flush=True)
        future = client.call_async(AddTwoInts.Request(a=2, b=3))
        rclpy.spin_until_future_complete(node, future)
        if future.result() is not None:
            node.get_logger().info(f"Result of add_two_ints: {future.result().sum}")
        elif cpp:
            node.get_logger().error("Interrupted while waiting for response. Exiting.")
        else:
            node.get_logger().error(f"Exception while calling service: {future.exception()!r}")
    except KeyboardInterrupt:
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
    return 0


def cpp_client() -> int:
    return _client(cpp=True)


def py_client() -> int:
    return _client(cpp=False)
