"""`launch_testing_ros.message_pump` (diffctl/testing/ros_helpers.py)."""

from diffctl.testing.ros_helpers import MessagePump

__all__ = ["MessagePump"]
