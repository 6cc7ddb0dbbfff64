"""`launch_testing_ros.wait_for_topics` (diffctl/testing/wait_for_topics.py)."""

from diffctl.testing.wait_for_topics import WaitForTopics

__all__ = ["WaitForTopics"]
