"""`launch_testing.test_runner` (diffctl/testing/test_runner.py)."""

from diffctl.testing.test_runner import LaunchTestRunner

__all__ = ["LaunchTestRunner"]
