"""`launch_testing.tools.text` (diffctl/testing/tools.py)."""

from diffctl.testing.tools import expect_output

__all__ = ["expect_output"]
