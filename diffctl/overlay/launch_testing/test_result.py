"""`launch_testing.test_result` (diffctl/testing/result.py)."""

from diffctl.testing.result import FailResult, SkipResult, TestResult

__all__ = ["FailResult", "SkipResult", "TestResult"]
