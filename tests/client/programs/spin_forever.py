# A node spinning with no exception handling: what Ctrl-C and SIGTERM do to it. With the argument `multi`, on a
# MultiThreadedExecutor, logging a line once spin has returned and one once the node is destroyed.
import sys

import rclpy
from rclpy.executors import MultiThreadedExecutor
from rclpy.node import Node

rclpy.init()
node = Node("spinner")
node.create_timer(0.01, lambda: None)
print("spinning", flush=True)
if sys.argv[1:] == ["multi"]:
    rclpy.spin(node, executor=MultiThreadedExecutor(num_threads=2))
    node.get_logger().info("spin returned")
    node.destroy_node()
    node.get_logger().info("node destroyed")
else:
    rclpy.spin(node)
