"""`launch_testing_ros` (diffctl/testing/): WaitForTopics, DataRepublisher, MessagePump, the output filters."""

from diffctl.testing.ros_helpers import DataRepublisher, MessagePump
from diffctl.testing.test_runner import LaunchTestRunner
from diffctl.testing.wait_for_topics import WaitForTopics

from . import tools  # noqa: F401

__all__ = ["DataRepublisher", "LaunchTestRunner", "MessagePump", "WaitForTopics"]
