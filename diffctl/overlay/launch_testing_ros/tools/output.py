"""`launch_testing_ros.tools.output` (diffctl/testing/ros_output.py)."""

from diffctl.testing.ros_output import basic_output_filter, get_rmw_output_filter

__all__ = ["basic_output_filter", "get_rmw_output_filter"]
