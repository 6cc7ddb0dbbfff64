"""`launch_pytest.actions`: launch_testing's ReadyToTest."""

from diffctl.testing.decorators import ReadyToTest

__all__ = ["ReadyToTest"]
