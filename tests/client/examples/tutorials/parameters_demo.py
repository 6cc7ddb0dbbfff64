# The parameter tutorial's node: a declared parameter with a descriptor, read in a timer, set back.
# ruff: noqa: UP031  (written as the ROS 2 tutorials write it)
import rclpy
import rclpy.node
from rcl_interfaces.msg import ParameterDescriptor


class MinimalParam(rclpy.node.Node):
    def __init__(self):
        super().__init__('minimal_param_node')
        self.declare_parameter('my_parameter', 'world', ParameterDescriptor(description='This parameter is mine!'))
        self.timer = self.create_timer(0.2, self.timer_callback)

    def timer_callback(self):
        my_param = self.get_parameter('my_parameter').get_parameter_value().string_value
        self.get_logger().info('Hello %s!' % my_param)


def main():
    rclpy.init()
    node = MinimalParam()
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass


if __name__ == '__main__':
    main()
