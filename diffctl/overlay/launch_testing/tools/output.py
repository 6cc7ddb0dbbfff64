"""`launch_testing.tools.output` (diffctl/testing/tools.py)."""

from diffctl.testing.tools import basic_output_filter, expect_output, expected_output_from_file

__all__ = ["basic_output_filter", "expect_output", "expected_output_from_file"]
