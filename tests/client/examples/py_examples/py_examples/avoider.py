import math

import rclpy
from geometry_msgs.msg import TwistStamped
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.qos import qos_profile_sensor_data
from sensor_msgs.msg import LaserScan


class Avoider(Node):
    """Drives forward and turns away from whatever the lidar sees ahead (a scan → cmd_vel node)."""

    def __init__(self):
        super().__init__('avoider')
        self.declare_parameter('speed', 0.3)
        self.declare_parameter('clearance', 0.6)
        self.pub = self.create_publisher(TwistStamped, '/diffbot_base_controller/cmd_vel', 10)
        self.sub = self.create_subscription(LaserScan, '/scan', self.on_scan, qos_profile_sensor_data)
        self.scans = 0

    def on_scan(self, scan: LaserScan):
        ahead = [r for i, r in enumerate(scan.ranges)
                 if abs(scan.angle_min + i * scan.angle_increment) < math.radians(30)
                 and scan.range_min <= r <= scan.range_max]
        nearest = min(ahead) if ahead else math.inf
        cmd = TwistStamped()
        cmd.header.stamp = self.get_clock().now().to_msg()
        cmd.header.frame_id = 'base_link'
        if nearest < self.get_parameter('clearance').value:
            cmd.twist.angular.z = 0.8
        else:
            cmd.twist.linear.x = self.get_parameter('speed').value
        self.pub.publish(cmd)
        self.scans += 1
        if self.scans == 1:
            self.get_logger().info(f'first scan: {len(scan.ranges)} ranges, nearest ahead {nearest:.2f} m')


def main():
    try:
        with rclpy.init():
            rclpy.spin(Avoider())
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
