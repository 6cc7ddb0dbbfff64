"""The oracle venv runs the real rclpy: a talker and a listener in two processes find each other over Fast DDS
on loopback with the environment jazzy_venv gives them (the setup every differential test relies on)."""

from __future__ import annotations

from tests.oracle import jazzy_venv

TALKER = r'''
import rclpy
from rclpy.node import Node
from std_msgs.msg import String
rclpy.init()
node = Node('talker')
pub = node.create_publisher(String, 'chatter', 10)
n = 0
def tick():
    global n
    n += 1
    pub.publish(String(data=f'Hello World: {n}'))
node.create_timer(0.05, tick)
rclpy.spin(node)
'''

LISTENER = r'''
import rclpy, rclpy.logging, os
from rclpy.node import Node
from std_msgs.msg import String
rclpy.init()
node = Node('listener')
got = []
node.create_subscription(String, 'chatter', lambda m: got.append(m.data), 10)
import time
deadline = time.monotonic() + 20
while not got and time.monotonic() < deadline:
    rclpy.spin_once(node, timeout_sec=0.1)
print(os.environ['RMW_IMPLEMENTATION'], rclpy.get_rmw_implementation_identifier(), got[:1])
'''


def test_real_talker_and_listener_on_loopback(procs) -> None:
    talker = jazzy_venv.start_python(TALKER, procs)
    out = jazzy_venv.run_python(LISTENER).stdout.strip()
    assert out.startswith("rmw_fastrtps_cpp rmw_fastrtps_cpp ['Hello World: "), out
    assert talker.poll() is None, "the talker must still be running"
