"""A Python composable node: a class taking **kwargs (node options) and passing them to rclpy's Node."""

from rclpy.node import Node


class Talker(Node):
    def __init__(self, **kwargs):
        super().__init__("talker", **kwargs)
        greeting = self.declare_parameter("greeting", "hi").value
        print(f"component {self.get_fully_qualified_name()} says {greeting}", flush=True)
