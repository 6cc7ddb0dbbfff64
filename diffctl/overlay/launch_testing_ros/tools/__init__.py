"""`launch_testing_ros.tools` (diffctl/testing/ros_output.py)."""

from diffctl.testing.ros_output import basic_output_filter, get_rmw_output_filter

from . import output  # noqa: F401

__all__ = ["basic_output_filter", "get_rmw_output_filter"]
