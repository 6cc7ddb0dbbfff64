"""Drives /lc_talker through configure and activate with the lifecycle services (as `ros2 lifecycle set`),
then listens to what it publishes."""

import sys

import rclpy
from lifecycle_msgs.msg import Transition
from lifecycle_msgs.srv import ChangeState, GetState
from rclpy.node import Node
from std_msgs.msg import String


def main():
    rclpy.init()
    node = Node('lc_manager')
    heard = []
    node.create_subscription(String, 'lifecycle_chatter', lambda m: heard.append(m.data), 10)
    change = node.create_client(ChangeState, '/lc_talker/change_state')
    get = node.create_client(GetState, '/lc_talker/get_state')
    if not change.wait_for_service(timeout_sec=20.0):
        print('no lifecycle node', flush=True)
        sys.exit(1)
    for transition in (Transition.TRANSITION_CONFIGURE, Transition.TRANSITION_ACTIVATE):
        future = change.call_async(ChangeState.Request(transition=Transition(id=transition)))
        rclpy.spin_until_future_complete(node, future, timeout_sec=10.0)
        print('transition', transition, future.result().success, flush=True)
    future = get.call_async(GetState.Request())
    rclpy.spin_until_future_complete(node, future, timeout_sec=10.0)
    print('state', future.result().current_state.label, flush=True)
    while len(heard) < 3:
        rclpy.spin_once(node, timeout_sec=1.0)
    print('heard', heard[0].startswith('Lifecycle HelloWorld #'), flush=True)
    node.destroy_node()
    rclpy.shutdown()
