"""A Python composable node (what diffctl's container loads): it takes the node options as keyword arguments.

On construction it appends one line to the file $COMPONENT_LOG: its full name, its `greeting` parameter and
where its `chatter` topic resolves."""

import os

from rclpy.node import Node


class Greeter(Node):
    def __init__(self, **kwargs):
        super().__init__("greeter", **kwargs)
        greeting = self.declare_parameter("greeting", "none").value
        topic = self.create_publisher(__import__("std_msgs.msg").msg.String, "chatter", 1).topic_name
        with open(os.environ["COMPONENT_LOG"], "a") as f:
            f.write(f"{self.get_fully_qualified_name()} greeting={greeting} chatter={topic}\n")
