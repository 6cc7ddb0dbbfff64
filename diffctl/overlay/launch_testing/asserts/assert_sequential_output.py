"""`launch_testing.asserts.assert_sequential_output` (diffctl/testing/asserts.py)."""

from diffctl.testing.asserts import SequentialTextChecker, assertSequentialStdout

__all__ = ["SequentialTextChecker", "assertSequentialStdout"]
