"""Test results as launch_testing keeps them: per test case, with its time, for the summary and JUnit XML."""

from __future__ import annotations

import time
import unittest
from typing import Any


class TestResult(unittest.TextTestResult):
    """unittest's verbose text result that also keeps each case's outcome and duration."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.testTimes: dict[Any, float] = {}
        self.successes: list[Any] = []
        self._started: dict[Any, float] = {}

    def startTest(self, test: Any) -> None:
        self._started[test] = time.monotonic()
        super().startTest(test)

    def stopTest(self, test: Any) -> None:
        self.testTimes[test] = time.monotonic() - self._started.get(test, time.monotonic())
        super().stopTest(test)

    def addSuccess(self, test: Any) -> None:
        self.successes.append(test)
        super().addSuccess(test)

    failure_hook: Any = None  # called with the test's id at each failure or error (the artifacts' picture)

    def addFailure(self, test: Any, err: Any) -> None:
        if self.failure_hook is not None:
            self.failure_hook(f"FAIL: {test.id()}")
        super().addFailure(test, err)

    def addError(self, test: Any, err: Any) -> None:
        if self.failure_hook is not None:
            self.failure_hook(f"ERROR: {test.id()}")
        super().addError(test, err)


class FailResult(unittest.TestResult):
    """A run whose launch ended before its tests did: every case fails, as launch_testing reports it."""

    def __init__(self, cases: list[Any], message: str = "Launch stopped before the active tests finished.") -> None:
        super().__init__()
        self.testsRun = len(cases)
        self.testTimes = {case: 0.0 for case in cases}
        self.successes: list[Any] = []
        self.failures = [(case, message) for case in cases]

    def wasSuccessful(self) -> bool:
        return False


class SkipResult(unittest.TestResult):
    """A run whose generate_test_description raised unittest.SkipTest: every case is skipped."""

    def __init__(self, cases: list[Any], reason: str) -> None:
        super().__init__()
        self.testsRun = len(cases)
        self.testTimes = {case: 0.0 for case in cases}
        self.successes: list[Any] = []
        self.skipped = [(case, reason) for case in cases]
