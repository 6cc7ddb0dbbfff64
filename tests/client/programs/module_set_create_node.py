# rclpy.create_node imports rclpy.node (the ros2/examples guard-condition example then uses rclpy.executors).
import json
import sys

import rclpy

rclpy.init()
node = rclpy.create_node("module_set_demo")
out = [["after create_node", sorted(k for k in sys.modules if k.startswith("rclpy"))],
       ["rclpy.executors", hasattr(rclpy, "executors")]]
node.destroy_node()
rclpy.shutdown()
print(json.dumps(out))
