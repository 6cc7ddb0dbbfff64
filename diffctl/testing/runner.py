"""diffctl's launch test runner: launch_testing's LaunchTestRunner with each run on a Zenoh router and ROS
domain of its own, each process's output kept as its log, and on failure the artifacts (`--artifacts`).

`run_file` runs every TestRun of a file and answers a FileResult: the runs' unittest results (as
launch_testing's runner gives them) plus, per run, the processes' logs and its duration, for JUnit XML.
"""

from __future__ import annotations

import contextlib
import os
import re
import sys
import tempfile
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from diffctl.launch_testing.test_result import TestResult
from diffctl.launch_testing.test_runner import LaunchTestRunner, _RunnerWorker
from diffctl.testing.loader import load


@dataclass
class RunRecord:
    """One run (one parametrization) of a test file: its result, its processes' output, its duration."""

    run: Any
    result: Any = None
    logs: dict[str, str] = field(default_factory=dict)  # '<process name>.log' → what it printed
    seconds: float = 0.0

    @property
    def ok(self) -> bool:
        return self.result is not None and self.result.wasSuccessful()


@dataclass
class FileResult:
    path: Path
    package_name: str
    runs: list[RunRecord] = field(default_factory=list)
    error: str | None = None

    @property
    def ok(self) -> bool:
        return self.error is None and all(r.ok for r in self.runs)


def _logs(proc_output: Any, log_dir: Path) -> dict[str, str]:
    """Each process's output, in a file named as `diffctl launch` names its logs (`gz_sim.log`: the run's
    processes keep launch_testing's `name-N`), and the log files the launch wrote (launch.log, own_log files)."""
    from diffctl.cli.launch import DiffctlLabels

    label = DiffctlLabels()
    logs: dict[str, str] = {}
    for action in proc_output.processes():
        name = action.process_details["name"]
        with contextlib.suppress(KeyError):
            text = "".join(e.text.decode(errors="replace") for e in proc_output[name])
            logs[f"{label(action, re.sub(r'-[0-9]+$', '', name))}.log"] = text
    for path in sorted(log_dir.glob("*.log")):
        logs.setdefault(path.name, path.read_text(errors="replace"))
    return logs


@contextlib.contextmanager
def _launch_log_dir() -> Iterator[Path]:
    """launch's log directory for one run: a fresh temporary one (read into the run's record, then removed)."""
    import diffctl.launch.logging as launch_logging

    with tempfile.TemporaryDirectory(prefix="launch-test-log-") as folder:
        launch_logging.reset()
        launch_logging.launch_config.log_dir = folder
        try:
            yield Path(folder)
        finally:
            launch_logging.reset()


def _with_failure_hook(hook: Callable[[str], None]) -> type:
    """launch_testing's TestResult, calling `hook` at the first failure or error (the artifacts' picture)."""

    class Result(TestResult):
        def addFailure(self, test: Any, err: Any) -> None:
            hook(f"FAIL: {test.id()}")
            super().addFailure(test, err)

        def addError(self, test: Any, err: Any) -> None:
            hook(f"ERROR: {test.id()}")
            super().addError(test, err)

    return Result


class IsolatedLaunchTestRunner(LaunchTestRunner):
    """LaunchTestRunner whose runs each get a bus of their own (`isolate`) and, with `artifacts`, a folder of
    logs, bag and scene picture when they fail. `records` holds each run's RunRecord once it ran."""

    def __init__(self, test_runs: list[Any], launch_file_arguments: Any = (), debug: bool = False, *,
                 isolate: bool = True, artifacts: Path | None = None) -> None:
        super().__init__(test_runs, launch_file_arguments, debug)
        self.isolate = isolate
        self.artifacts = artifacts
        self.records: dict[Any, RunRecord] = {}
        self._worker: _RunnerWorker | None = None
        self._spawner: Any = None
        self._kept: Any = None

    @contextlib.contextmanager
    def _run_scope(self, test_run: Any) -> Iterator[None]:
        if not self.isolate:
            yield
            return
        from diffctl.testing.isolation import isolated_bus

        with isolated_bus() as bus:
            print(f"Running with ROS_DOMAIN_ID {bus.domain_id} on the router {bus.endpoint}")
            sys.stdout.flush()
            yield

    def _new_worker(self, test_run: Any) -> _RunnerWorker:
        from diffctl.launch import LaunchService

        result_class = TestResult if self._kept is None else _with_failure_hook(self._kept.on_failure)
        service = LaunchService(debug=self._debug, spawner=self._spawner_for_run())
        self._worker = _RunnerWorker(test_run, self.generate_preamble(), self._launch_file_arguments, self._debug,
                                     result_class=result_class, launch_service=service)
        return self._worker

    def _spawner_for_run(self) -> Any:
        """diffctl launch's spawner: every process dies with the test (death signal, guard), orphans are
        reaped, and diffctl's components are forked from the test's own fork server when it has one (a test
        forked from `diffctl test`'s zygote; its first run)."""
        from diffctl.launch import logging as launch_logging
        from diffctl.supervision.launcher_spawner import LauncherSpawner
        from diffctl.testing.zygotes import take_inherited

        self._spawner = LauncherSpawner(fork_server=take_inherited(dict(os.environ)),
                                        logger=launch_logging.get_logger("launch"))
        return self._spawner

    def _run_one(self, test_run: Any) -> Any:
        record = RunRecord(test_run)
        self.records[test_run] = record
        started = time.monotonic()
        self._worker = None
        with self._run_scope(test_run), self._artifacts_of(test_run), _launch_log_dir() as log_dir:
            try:
                record.result = self._new_worker(test_run).run()
                return record.result
            finally:
                if self._spawner is not None:
                    self._spawner.close()  # its fork server and guard
                    self._spawner = None
                record.seconds = time.monotonic() - started
                if self._worker is not None:
                    record.logs = _logs(self._worker.proc_output, log_dir)

    @contextlib.contextmanager
    def _artifacts_of(self, test_run: Any) -> Iterator[None]:
        if self.artifacts is None:
            yield
            return
        from diffctl.testing.artifacts import Artifacts

        label = re.sub(r"[^\w.=-]+", "_", str(test_run))
        target = self.artifacts / label if len(self._test_runs) > 1 else self.artifacts
        with tempfile.TemporaryDirectory(prefix="launch-test-artifacts-") as work:
            self._kept = Artifacts(target, Path(work))
            record = self.records[test_run]
            try:
                yield
            finally:
                failed = not record.ok
                self._kept.finish(failed, record.logs)
                if failed:
                    print(f"artifacts of {test_run}: {target}")
                self._kept = None

    def run(self) -> dict[Any, Any]:
        results = super().run()
        for test_run, result in results.items():  # skipped and died runs get their result here
            self.records.setdefault(test_run, RunRecord(test_run)).result = result
        return results


def run_file(path: Path, arguments: list[str] | None = None, *, package_name: str | None = None,
             isolate: bool = True, artifacts: Path | None = None, debug: bool = False) -> FileResult:
    """Every run of the launch test file at `path` (LaunchTestErrors for a file that cannot run)."""
    path = Path(path).resolve()
    basename = path.name[:-3] if path.name.endswith(".py") else path.name
    package_name = package_name or basename
    _, runs = load(path, package_name)
    runner = IsolatedLaunchTestRunner(runs, list(arguments or []), debug, isolate=isolate, artifacts=artifacts)
    runner.validate()
    runner.run()
    return FileResult(path, package_name, [runner.records[r] for r in runs if r in runner.records])
