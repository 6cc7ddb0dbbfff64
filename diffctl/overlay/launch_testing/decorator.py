"""`launch_testing.decorator` (diffctl/testing/decorators.py)."""

from diffctl.testing.decorators import post_shutdown_test

__all__ = ["post_shutdown_test"]
