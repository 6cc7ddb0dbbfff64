"""launch_testing's programmatic API: `LaunchTestRunner(test_runs, launch_file_arguments).run()` over diffctl's
runner, each run on a router and domain of its own, and the combined unittest result of each run."""

from __future__ import annotations

import io
import sys
import tempfile
import unittest
from pathlib import Path
from typing import Any

from diffctl.testing.loader import TestRun
from diffctl.testing.parse_arguments import parse_launch_arguments
from diffctl.testing.result import TestResult


def combine(results: list[unittest.TestResult]) -> TestResult:
    """One result out of a run's pre- and post-shutdown results (launch_testing hands back one per run)."""
    out = TestResult(io.StringIO(), True, 1)
    for r in results:
        out.testsRun += r.testsRun
        for attr in ("failures", "errors", "skipped", "expectedFailures", "unexpectedSuccesses", "successes"):
            getattr(out, attr).extend(getattr(r, attr, []))
        out.testTimes.update(getattr(r, "testTimes", {}))
    return out


class LaunchTestRunner:
    """Runs TestRuns (from `loader.LoadTestsFromPythonModule`) one after the other, as launch_testing's."""

    def __init__(self, test_runs: list[TestRun], launch_file_arguments: list[str] | tuple[str, ...] = (),
                 debug: bool = False) -> None:
        self._test_runs = list(test_runs)
        self._launch_file_arguments = list(launch_file_arguments)
        self._debug = debug

    def validate(self) -> None:
        """Raise when there is nothing to run or an argument is not NAME:=VALUE, before anything starts."""
        if not self._test_runs:
            raise Exception("No test runs to run")
        for argument in self._launch_file_arguments:
            if ":=" not in argument or argument.startswith(":="):
                raise Exception(f"malformed launch argument {argument!r}, expected format '<name>:=<value>'")

    def run(self) -> dict[TestRun, TestResult]:
        from diffctl.testing.isolation import isolated_bus
        from diffctl.testing.runner import run_once

        arguments = dict(parse_launch_arguments(self._launch_file_arguments))
        results: dict[TestRun, TestResult] = {}
        with tempfile.TemporaryDirectory(prefix="launch-test-") as tmp:
            for index, run in enumerate(self._test_runs):
                with isolated_bus():
                    one = run_once(run, arguments, log_dir=Path(tmp) / f"run{index}", stdout=sys.stdout,
                                   stderr=sys.stderr)
                results[run] = combine(one.results)
                if one.failed_early:
                    break
        return results

    @property
    def debug(self) -> Any:
        return self._debug
