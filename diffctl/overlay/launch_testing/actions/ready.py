"""`launch_testing.actions.ready` (diffctl/testing/decorators.py)."""

from diffctl.testing.decorators import ReadyToTest

__all__ = ["ReadyToTest"]
