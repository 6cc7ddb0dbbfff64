# rcl's logging switches in --ros-args: no console lines, no /rosout publisher, a logger's level by name.
import json
import time

import rclpy
from rclpy.node import Node

rclpy.init(args=["prog", "--ros-args", "--disable-rosout-logs", "--log-level", "switches.child:=debug"])
node = Node("switches")
node.get_logger().info("still on the console")
node.get_logger().get_child("child").debug("a child's debug line")
node.get_logger().debug("not at the node's level")
time.sleep(1.0)
out = [["rosout publishers of this node", [t for t, _ in node.get_publisher_names_and_types_by_node(
    "switches", "/") if t == "/rosout"]],
       ["levels", [int(node.get_logger().get_effective_level()),
                   int(node.get_logger().get_child("child").get_effective_level())]]]
node.destroy_node()
rclpy.shutdown()
print(json.dumps(out))
