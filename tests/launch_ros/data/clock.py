"""Publishes /clock: 10 s of simulated time per message, a message every 20 ms of wall time, until interrupted."""

import rclpy
from rclpy.executors import ExternalShutdownException
from rosgraph_msgs.msg import Clock

rclpy.init()
node = rclpy.create_node("sim_clock")
publisher = node.create_publisher(Clock, "/clock", 10)
seconds = [0]


def tick():
    seconds[0] += 10
    msg = Clock()
    msg.clock.sec = seconds[0]
    publisher.publish(msg)


node.create_timer(0.02, tick)
try:
    rclpy.spin(node)
except (KeyboardInterrupt, ExternalShutdownException):
    pass
finally:
    rclpy.try_shutdown()
