"""parameter_blackboard: a node that accepts any parameter (demo_nodes_cpp), the peer of async_param_client."""

from __future__ import annotations

from rcl_interfaces.srv import ListParameters
from rclpy.node import Node

from diffctl.demo_nodes.spin import spin_node


class Blackboard(Node):
    def __init__(self) -> None:
        super().__init__(
            "parameter_blackboard",
            allow_undeclared_parameters=True,
            automatically_declare_parameters_from_overrides=True,
        )
        count = len(self.list_parameters([], ListParameters.Request.DEPTH_RECURSIVE).names)
        self.get_logger().info(
            f"Parameter blackboard node named '{self.get_fully_qualified_name()}' ready, "
            f"and serving '{count}' parameters already!"
        )


def blackboard() -> int:
    return spin_node(Blackboard)
