"""`launch_testing_ros.test_runner`: every run already has a router and ROS_DOMAIN_ID of its own here."""

from diffctl.testing.test_runner import LaunchTestRunner

__all__ = ["LaunchTestRunner"]
