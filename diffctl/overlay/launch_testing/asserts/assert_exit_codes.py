"""`launch_testing.asserts.assert_exit_codes` (diffctl/testing/asserts.py)."""

from diffctl.testing.asserts import (
    EXIT_FORCED,
    EXIT_OK,
    EXIT_SIGINT,
    EXIT_SIGKILL,
    EXIT_SIGQUIT,
    EXIT_SIGSEGV,
    assertExitCodes,
)

__all__ = ["EXIT_FORCED", "EXIT_OK", "EXIT_SIGINT", "EXIT_SIGKILL", "EXIT_SIGQUIT", "EXIT_SIGSEGV", "assertExitCodes"]
