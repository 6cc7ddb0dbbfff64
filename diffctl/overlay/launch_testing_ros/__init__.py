"""`launch_testing_ros` (diffctl/testing/): WaitForTopics, the output filters, LaunchTestRunner."""

from diffctl.testing.wait_for_topics import WaitForTopics

from . import tools  # noqa: F401

__all__ = ["WaitForTopics"]
