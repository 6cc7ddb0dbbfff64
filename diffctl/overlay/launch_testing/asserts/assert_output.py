"""`launch_testing.asserts.assert_output` (diffctl/testing/asserts.py)."""

from diffctl.testing.asserts import assertDefaultStream, assertInStderr, assertInStdout, assertInStream

__all__ = ["assertDefaultStream", "assertInStderr", "assertInStdout", "assertInStream"]
