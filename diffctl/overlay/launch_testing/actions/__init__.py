"""`launch_testing.actions` (diffctl/testing/decorators.py)."""

from diffctl.testing.decorators import ReadyToTest

from . import ready  # noqa: F401

__all__ = ["ReadyToTest"]
