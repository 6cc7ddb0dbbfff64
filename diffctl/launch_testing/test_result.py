"""unittest results as launch_test keeps them: every case that ran, with its duration (for JUnit XML), and
the results of runs whose tests never ran (the launch died, or the description was skipped)."""

from __future__ import annotations

import time
import unittest
from typing import Any

# unittest.TestResult's lists of (case, text) outcomes, merged when one result takes in another
_OUTCOME_LISTS = ("failures", "errors", "skipped", "expectedFailures", "unexpectedSuccesses")


class FailResult(unittest.TestResult):
    """A run whose processes stopped before its tests finished: every test of it fails with `message`."""

    def __init__(self, test_run: Any, message: str) -> None:
        super().__init__()
        for case in test_run.all_cases():
            self.addFailure(case, (Exception, Exception(message), None))
            self.testsRun += 1

    @property
    def testCases(self) -> list[Any]:
        return [case for case, _ in self.failures]

    @property
    def testTimes(self) -> dict[Any, float]:
        return {case: 0 for case, _ in self.failures}

    def wasSuccessful(self) -> bool:
        return False


class SkipResult(unittest.TestResult):
    """A run whose generate_test_description is skipped (unittest.skip): every test of it is skipped."""

    def __init__(self, test_run: Any, skip_reason: str = "") -> None:
        super().__init__()
        for case in test_run.all_cases():
            self.addSkip(case, skip_reason)
            self.testsRun += 1

    @property
    def testCases(self) -> list[Any]:
        return [case for case, _ in self.skipped]

    @property
    def testTimes(self) -> dict[Any, float]:
        return {case: 0 for case, _ in self.skipped}

    def wasSuccessful(self) -> bool:
        return True


class TestResult(unittest.TextTestResult):
    """unittest's text result that also records each case it ran and when it started and stopped."""

    def __init__(self, stream: Any = None, descriptions: Any = None, verbosity: Any = None) -> None:
        self.__spans: dict[Any, list[float]] = {}
        super().__init__(stream, descriptions, verbosity)

    @property
    def testCases(self) -> Any:
        return self.__spans.keys()

    @property
    def testTimes(self) -> dict[Any, float]:
        return {case: end - start for case, (start, end) in self.__spans.items()}

    def startTest(self, test: Any) -> None:
        self.__spans[test] = [time.time(), 0.0]
        super().startTest(test)

    def stopTest(self, test: Any) -> None:
        self.__spans[test][1] = time.time()
        super().stopTest(test)

    def append(self, results: TestResult) -> None:
        """Take in another result's cases and outcomes (a run's post-shutdown results into its active ones)."""
        self.__spans.update(results.__spans)
        self.testsRun += results.testsRun
        for outcome in _OUTCOME_LISTS:
            getattr(self, outcome).extend(getattr(results, outcome))
