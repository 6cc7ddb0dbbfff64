"""launch_testing.actions: ReadyToTest, and test processes run by a launch (GTest, PyTest)."""

from .gtest import GTest
from .pytest import PyTest
from .ready import ReadyToTest

__all__ = ["GTest", "PyTest", "ReadyToTest"]
