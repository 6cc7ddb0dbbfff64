"""A managed node as users write them with rclpy.lifecycle (run through diffctl's overlay rclpy)."""

import rclpy
from rclpy.lifecycle import Node, State, TransitionCallbackReturn


class Managed(Node):
    def on_configure(self, state: State) -> TransitionCallbackReturn:
        print("configuring", flush=True)
        return TransitionCallbackReturn.SUCCESS

    def on_activate(self, state: State) -> TransitionCallbackReturn:
        print("activating", flush=True)
        return super().on_activate(state)


rclpy.init()
node = Managed("managed")
try:
    rclpy.spin(node)
except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
    pass
