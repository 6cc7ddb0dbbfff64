# A node spinning with no exception handling: what Ctrl-C and SIGTERM do to it.
import rclpy
from rclpy.node import Node

rclpy.init()
node = Node("spinner")
node.create_timer(0.01, lambda: None)
print("spinning", flush=True)
rclpy.spin(node)
