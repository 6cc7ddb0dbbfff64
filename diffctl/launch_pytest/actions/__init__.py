"""launch_pytest.actions: ReadyToTest (launch_testing's)."""

from diffctl.launch_testing.actions import ReadyToTest

__all__ = ["ReadyToTest"]
