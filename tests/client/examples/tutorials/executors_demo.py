# Two nodes in one process on a MultiThreadedExecutor: a talker, and a listener whose slow callbacks run in
# a reentrant group so a second timer keeps its rate (the executors demo of the ROS 2 docs).
import time

import rclpy
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import MultiThreadedExecutor
from rclpy.node import Node
from std_msgs.msg import String


class Talker(Node):
    def __init__(self):
        super().__init__('talker')
        self.i = 0
        self.pub = self.create_publisher(String, 'chatter', 10)
        self.timer = self.create_timer(0.05, self.tick)

    def tick(self):
        self.i += 1
        self.pub.publish(String(data=f'Hello World: {self.i}'))


class Listener(Node):
    def __init__(self):
        super().__init__('listener')
        group = ReentrantCallbackGroup()
        self.heard = 0
        self.beats = 0
        self.sub = self.create_subscription(String, 'chatter', self.on_msg, 10, callback_group=group)
        self.timer = self.create_timer(0.02, self.beat, callback_group=group)

    def on_msg(self, msg):
        self.heard += 1
        time.sleep(0.045)  # slow work; the heartbeat still runs in another thread

    def beat(self):
        self.beats += 1


def main():
    rclpy.init()
    talker, listener = Talker(), Listener()
    executor = MultiThreadedExecutor(num_threads=4)
    executor.add_node(talker)
    executor.add_node(listener)
    end = time.monotonic() + 1.5
    while time.monotonic() < end:
        executor.spin_once(timeout_sec=0.05)
    listener.get_logger().info(f'heard {listener.heard} messages, {listener.beats} heartbeats')
    executor.shutdown()
    talker.destroy_node()
    listener.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
