"""`launch_testing.actions` (diffctl/testing/decorators.py)."""

from diffctl.testing.decorators import ReadyToTest

__all__ = ["ReadyToTest"]
