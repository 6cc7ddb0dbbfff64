"""A managed node named by its --ros-args (rclpy's lifecycle API), spinning until interrupted."""

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.lifecycle import Node, TransitionCallbackReturn


class Managed(Node):
    def on_configure(self, state):
        return TransitionCallbackReturn.SUCCESS

    def on_activate(self, state):
        return TransitionCallbackReturn.SUCCESS


rclpy.init()
node = Managed("managed")
try:
    rclpy.spin(node)
except (KeyboardInterrupt, ExternalShutdownException):
    pass
finally:
    rclpy.try_shutdown()
