import math

import rclpy
from rclpy.node import Node
from rclpy.time import Time
from tf2_ros import TransformException
from tf2_ros.buffer import Buffer
from tf2_ros.transform_listener import TransformListener


class FrameListener(Node):
    """Looks the carrot up in the world frame until it has seen it five times, then exits."""

    def __init__(self):
        super().__init__('carrot_listener')
        self.target_frame = self.declare_parameter('target_frame', 'carrot1').get_parameter_value().string_value
        self.tf_buffer = Buffer()
        self.tf_listener = TransformListener(self.tf_buffer, self)
        self.seen = 0
        self.timer = self.create_timer(0.1, self.on_timer)

    def on_timer(self):
        try:
            t = self.tf_buffer.lookup_transform('world', self.target_frame, Time())
        except TransformException as ex:
            self.get_logger().info(f'Could not transform world to {self.target_frame}: {ex}')
            return
        # The carrot circles turtle1 (x = 1) at a radius of 2.
        radius = math.hypot(t.transform.translation.x - 1.0, t.transform.translation.y)
        self.get_logger().info(f'carrot at radius {radius:.3f}')
        self.seen += 1
        if self.seen >= 5:
            print(f'seen carrot1 in world, radius {radius:.3f}', flush=True)
            raise SystemExit(0)


def main():
    rclpy.init()
    node = FrameListener()
    try:
        rclpy.spin(node)
    except SystemExit:
        pass
    node.destroy_node()
    rclpy.try_shutdown()
