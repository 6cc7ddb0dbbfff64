"""launch_testing_ros' talker/listener test as its example writes it: rclpy in the test bodies publishes to
the listener and hears the talker; WaitForTopics; exit codes after shutdown."""

import os
import sys
import time
import unittest
import uuid

import launch_ros.actions
import launch_testing.actions
import launch_testing.asserts
import launch_testing_ros
import pytest
import rclpy
from std_msgs.msg import String

import launch

HERE = os.path.dirname(os.path.abspath(__file__))


@pytest.mark.rostest
def generate_test_description():
    talker = launch_ros.actions.Node(
        executable=sys.executable, arguments=[os.path.join(HERE, "talker.py")],
        additional_env={"PYTHONUNBUFFERED": "1"}, name="talker", output="screen",
    )
    listener = launch_ros.actions.Node(
        executable=sys.executable, arguments=[os.path.join(HERE, "listener.py")],
        additional_env={"PYTHONUNBUFFERED": "1"}, name="listener", output="screen",
        remappings=[("chatter", "listener_chatter")],
    )
    return launch.LaunchDescription([talker, listener, launch_testing.actions.ReadyToTest()]), {
        "talker": talker, "listener": listener,
    }


class TestTalkerListenerLink(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rclpy.init()

    @classmethod
    def tearDownClass(cls):
        rclpy.shutdown()

    def setUp(self):
        self.node = rclpy.create_node("test_talker_listener_link")

    def tearDown(self):
        self.node.destroy_node()

    def test_talker_transmits(self, talker, proc_output):
        msgs_rx = []
        sub = self.node.create_subscription(String, "chatter", lambda msg: msgs_rx.append(msg), 10)
        try:
            end_time = time.time() + 10
            while time.time() < end_time and len(msgs_rx) <= 2:
                rclpy.spin_once(self.node, timeout_sec=0.1)
            self.assertGreater(len(msgs_rx), 2)
            for msg in msgs_rx:
                proc_output.assertWaitFor(expected_output=msg.data, process=talker, stream="stdout")
        finally:
            self.node.destroy_subscription(sub)

    def test_listener_receives(self, listener, proc_output):
        pub = self.node.create_publisher(String, "listener_chatter", 10)
        try:
            end_time = time.time() + 10
            while pub.get_subscription_count() == 0 and time.time() < end_time:
                time.sleep(0.05)  # the listener's subscription is matched: what is published now arrives
            msg = String(data=str(uuid.uuid4()))
            pub.publish(msg)
            proc_output.assertWaitFor(expected_output=msg.data, process=listener, timeout=10, stream="stdout")
        finally:
            self.node.destroy_publisher(pub)

    def test_republished_data(self, listener, proc_output):
        def shout(msg):
            return String(data=msg.data.upper()) if msg.data.endswith(("0", "2", "4", "6", "8")) else None

        republisher = launch_testing_ros.DataRepublisher(self.node, "chatter", "listener_chatter", String, shout)
        pump = launch_testing_ros.MessagePump(self.node)
        pump.start()
        try:
            proc_output.assertWaitFor("I heard: [HELLO WORLD:", process=listener, timeout=10, stream="stdout")
            end_time = time.time() + 10
            while time.time() < end_time and republisher.get_num_received() < 4:
                time.sleep(0.05)
            self.assertGreater(republisher.get_num_received(), republisher.get_num_republished())  # odd ones dropped
            self.assertGreaterEqual(republisher.get_num_republished(), 1)
        finally:
            pump.stop()
            republisher.shutdown()

    def test_wait_for_topics(self):
        with launch_testing_ros.WaitForTopics([("chatter", String)], timeout=10.0) as wait:
            self.assertEqual(wait.topics_not_received(), set())
            self.assertTrue(wait.received_messages("chatter")[0].data.startswith("Hello World"))
        silent = launch_testing_ros.WaitForTopics([("nobody_talks_here", String)], timeout=0.5)
        try:
            self.assertFalse(silent.wait())
            self.assertEqual(silent.topics_not_received(), {"nobody_talks_here"})
        finally:
            silent.shutdown()


@launch_testing.post_shutdown_test()
class TestShutdown(unittest.TestCase):
    def test_exit_codes(self, proc_info):
        launch_testing.asserts.assertExitCodes(proc_info)
