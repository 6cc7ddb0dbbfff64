"""`launch_testing_ros.data_republisher` (diffctl/testing/ros_helpers.py)."""

from diffctl.testing.ros_helpers import DataRepublisher

__all__ = ["DataRepublisher"]
