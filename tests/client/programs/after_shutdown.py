# Publishing after the context is shut down (a callback still running at Ctrl-C): rclpy's RCLError.
import json

import rclpy
from rclpy.node import Node
from std_msgs.msg import String

out = []
rclpy.init()
node = Node("late_publisher")
pub = node.create_publisher(String, "late", 10)
pub.publish(String(data="before"))
rclpy.shutdown()
try:
    pub.publish(String(data="after"))
    out.append(["publish after shutdown", None])
except Exception as e:
    out.append(["publish after shutdown", [type(e).__name__, str(e)]])
print(json.dumps(out))
