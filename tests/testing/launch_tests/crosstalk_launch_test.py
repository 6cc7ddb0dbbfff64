"""Each copy of this test publishes its own token on /crosstalk and must hear only its own: run twice at once
(`diffctl test -j 2`), the copies share topic names but not a bus."""

import os
import sys
import time
import unittest
import uuid

import launch.actions
import launch_testing.actions
import pytest
import rclpy
from std_msgs.msg import String

import launch

HERE = os.path.dirname(os.path.abspath(__file__))
TOKEN = str(uuid.uuid4())


@pytest.mark.launch_test
def generate_test_description():
    code = (
        "import sys, rclpy\nfrom std_msgs.msg import String\nrclpy.init()\nn = rclpy.create_node('pub')\n"
        "p = n.create_publisher(String, 'crosstalk', 10)\n"
        "n.create_timer(0.05, lambda: p.publish(String(data=sys.argv[1])))\n"
        "try:\n    rclpy.spin(n)\nexcept KeyboardInterrupt:\n    pass\n"
    )
    pub = launch.actions.ExecuteProcess(cmd=[sys.executable, "-c", code, TOKEN], name="pub")
    return launch.LaunchDescription([pub, launch_testing.actions.ReadyToTest()])


class TestOnlyOwnMessages(unittest.TestCase):
    def test_hears_only_itself(self):
        print(f"bus {os.environ['DIFFCTL_ROUTER']} domain {os.environ['ROS_DOMAIN_ID']}", flush=True)
        rclpy.init()
        try:
            node = rclpy.create_node("listen")
            heard = []
            node.create_subscription(String, "crosstalk", lambda m: heard.append(m.data), 10)
            end = time.monotonic() + 30.0  # a bound for a loaded machine: the loop ends at the 20th message
            while time.monotonic() < end and len(heard) < 20:
                rclpy.spin_once(node, timeout_sec=0.05)
            node.destroy_node()
        finally:
            rclpy.shutdown()
        self.assertGreater(len(heard), 10)
        self.assertEqual(set(heard), {TOKEN})
