# A node whose timer callback raises: rclpy.spin propagates it and Python prints the user's traceback.
import rclpy
from rclpy.node import Node


def broken_callback():
    values = {}
    return values["missing"]


rclpy.init()
node = Node("raiser")
node.create_timer(0.05, broken_callback)
rclpy.spin(node)
