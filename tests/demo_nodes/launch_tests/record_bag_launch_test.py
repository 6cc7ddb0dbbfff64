"""A launch test recording the C++ demo talker with `ros2 bag record`, the way the ROS docs' examples do."""

import os
import time
import unittest

import launch_ros.actions
import launch_testing.actions
import launch_testing.markers
import pytest

import launch


@pytest.mark.launch_test
@launch_testing.markers.keep_alive
def generate_test_description():
    talker = launch_ros.actions.Node(package="demo_nodes_cpp", executable="talker", name="demo_node")
    record = launch.actions.ExecuteProcess(
        cmd=["ros2", "bag", "record", "-o", os.environ["BAG_DIR"], "/chatter"], output="screen"
    )
    return launch.LaunchDescription([talker, record, launch_testing.actions.ReadyToTest()])


class TestRecordFor(unittest.TestCase):
    def test_wait_for_messages(self, proc_output):
        proc_output.assertWaitFor("Hello World: 2", timeout=30)
        time.sleep(1.0)
