"""`launch_testing.tools` (diffctl/testing/tools.py)."""

from diffctl.testing.tools import (
    ProcessProxy,
    basic_output_filter,
    expect_output,
    expected_output_from_file,
    launch_process,
)

from . import output, process, text  # noqa: F401

__all__ = ["ProcessProxy", "basic_output_filter", "expect_output", "expected_output_from_file", "launch_process"]
