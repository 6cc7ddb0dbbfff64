"""Running a launch test file as `launch_test` does: for each run, launch, test while it runs, shut down,
test after.

The launch runs on its thread (service.py); the tests that run while it does run on a thread of their own, so
a launch that ends first (every process exited, the ReadyToTest timeout) is noticed at once and fails every
case with launch_testing's message; `post_shutdown_test` classes run after, on the calling thread. Launch and
process output go to stdout, unittest's verbose lines and summary to stderr, as launch_test prints them.
"""

from __future__ import annotations

import contextlib
import os
import re
import sys
import tempfile
import threading
import time
import unittest
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TextIO

from diffctl.launch_legacy.actions import LaunchDescription
from diffctl.launch_legacy.event_handlers import OnProcessExit, OnProcessIO, OnProcessStart, RegisterEventHandler
from diffctl.launch_legacy.output import Output
from diffctl.testing.handlers import (
    ActiveIoHandler,
    ActiveProcInfoHandler,
    cache_output,
    record_exit,
    set_process_details,
)
from diffctl.testing.loader import TestRun, import_test_module, iterate_cases, load_test_runs, module_name_for
from diffctl.testing.result import FailResult, SkipResult, TestResult
from diffctl.testing.service import LaunchService


@dataclass
class RunResult:
    """What one run (one parametrization) of a test file gave."""

    run: TestRun
    results: list[unittest.TestResult] = field(default_factory=list)
    proc_info: ActiveProcInfoHandler | None = None
    proc_output: ActiveIoHandler | None = None
    log_dir: Path | None = None
    seconds: float = 0.0
    failed_early: bool = False
    logs: dict[str, str] = field(default_factory=dict)  # log file name → text, read before the folder may go

    @property
    def ok(self) -> bool:
        return all(r.wasSuccessful() for r in self.results)


@dataclass
class FileResult:
    path: Path
    package_name: str
    runs: list[RunResult] = field(default_factory=list)
    error: str | None = None

    @property
    def ok(self) -> bool:
        return self.error is None and all(r.ok for r in self.runs)


def _processes(description: Any, proc_info: ActiveProcInfoHandler, proc_output: ActiveIoHandler) -> LaunchDescription:
    """The test's description behind launch_testing's handlers (registered first, so the test's own run first)."""

    def started(event: Any, context: Any) -> None:
        set_process_details(event)
        proc_info.append(event)
        proc_output.track(event)

    def exited(event: Any, context: Any) -> None:
        record_exit(event)
        proc_info.append(event)

    def output(event: Any) -> None:
        cache_output(event)
        proc_output.append(event)

    return LaunchDescription(
        [
            RegisterEventHandler(OnProcessStart(on_start=started)),
            RegisterEventHandler(OnProcessExit(on_exit=exited)),
            RegisterEventHandler(OnProcessIO(on_stdout=output, on_stderr=output)),
            description,
        ]
    )


def _print_process_summary(proc_info: ActiveProcInfoHandler, proc_output: ActiveIoHandler, out: TextIO) -> None:
    for action in proc_info.processes():
        info = proc_info[action]
        code = getattr(info, "returncode", None)
        if code in (None, 0):
            continue
        name = info.name
        print(f"Process '{name}' exited with {code}", file=out)
        print(f"##### '{name}' output #####", file=out)
        with contextlib.suppress(KeyError):
            for io in proc_output[action]:
                print(io.text.decode(errors="replace").rstrip("\n"), file=out)
        print("#" * (len(name) + 21), file=out)


def run_once(
    run: TestRun,
    arguments: dict[str, str],
    *,
    log_dir: Path,
    stdout: TextIO | None = None,
    stderr: TextIO | None = None,
    shutdown_timeout_s: float = 30.0,
    on_failure: Callable[[str], None] | None = None,
) -> RunResult:
    """Launch one run of a test file, run its tests, shut it down and run its post-shutdown tests."""
    stdout = stdout or sys.stdout
    stderr = stderr or sys.stderr
    result = RunResult(run, log_dir=log_dir)
    started_at = time.monotonic()
    ready = threading.Event()
    try:
        description, context = run.description(ready.set)
    except unittest.SkipTest as e:
        print(f"{run} is skipped: {e}", file=stdout)
        result.results.append(SkipResult(list(run.all_cases()), str(e)))
        return result
    proc_info, proc_output = ActiveProcInfoHandler(), ActiveIoHandler()
    result.proc_info, result.proc_output = proc_info, proc_output
    output = Output(log_dir=log_dir, stream=stdout, live=False, no_color=not stdout.isatty())
    service = LaunchService(
        _processes(description, proc_info, proc_output),
        arguments,
        source=str(getattr(run, "source", "<launch test>")),
        log_dir=log_dir,
        output=output,
        shutdown_when_idle=not run.markers.get("keep_alive", False),
    )
    test_args = dict(arguments)
    values = {**context, **run.param_args}
    common = {"proc_info": proc_info, "proc_output": proc_output, "test_args": test_args}
    run.bind(run.pre_shutdown_tests, {**values, **common, "launch_service": service},
             {**common, "launch_service": service})
    run.bind(run.post_shutdown_tests, {**values, **common}, common)
    resultclass = TestResult
    if on_failure is not None:
        resultclass = type("TestResult", (TestResult,), {"failure_hook": staticmethod(on_failure)})
    runner = unittest.TextTestRunner(stream=stderr, verbosity=2, resultclass=resultclass)
    done = threading.Event()
    pre: list[unittest.TestResult] = []

    def active_tests() -> None:
        try:
            if not ready.wait(run.timeout_s) and service.running:
                print("Timed out waiting for processes to start up", file=stdout)
                return
            if not ready.is_set():
                return
            pre.append(runner.run(run.pre_shutdown_tests))
            done.set()
        finally:
            service.shutdown()

    tests = threading.Thread(target=active_tests, name="launch_test_active", daemon=True)
    try:
        service.start()
        tests.start()
        service.wait()
        if service.error is not None:
            raise service.error
    finally:
        service.shutdown()
        if not service.wait(shutdown_timeout_s):
            service.kill()
            service.wait(5.0)
        output.close()
        result.logs = read_logs(log_dir)
    if not done.is_set():
        # The launch ended before the active tests did (processes all exited, or never got ready).
        print("Processes under test stopped before tests completed", file=stdout)
        _print_process_summary(proc_info, proc_output, stdout)
        result.failed_early = True
        if on_failure is not None:
            on_failure("Processes under test stopped before tests completed")
        result.results.append(FailResult(list(run.all_cases())))
        result.seconds = time.monotonic() - started_at
        return result
    tests.join(1.0)
    result.results.extend(pre)
    result.results.append(runner.run(run.post_shutdown_tests))
    result.seconds = time.monotonic() - started_at
    return result


def read_logs(log_dir: Path) -> dict[str, str]:
    if not log_dir.is_dir():
        return {}
    return {p.name: p.read_text(errors="replace") for p in sorted(log_dir.glob("*.log"))}


@contextlib.contextmanager
def _log_root(log_dir: Path | None) -> Iterator[Path]:
    if log_dir is not None:
        log_dir.mkdir(parents=True, exist_ok=True)
        yield log_dir
        return
    with tempfile.TemporaryDirectory(prefix="diffctl-launch-test-") as tmp:
        yield Path(tmp)


def run_file(
    path: Path,
    arguments: dict[str, str] | None = None,
    *,
    package_name: str | None = None,
    log_dir: Path | None = None,
    isolate: bool = True,
    artifacts: Path | None = None,
    stdout: TextIO | None = None,
    stderr: TextIO | None = None,
) -> FileResult:
    """Every run of the launch test file at `path`, each on a bus of its own when `isolate`."""
    from diffctl.testing.isolation import isolated_bus

    arguments = dict(arguments or {})
    path = Path(path).resolve()
    package_name = package_name or module_name_for(path)
    file_result = FileResult(path, package_name)
    stdout = stdout or sys.stdout
    module = import_test_module(path, package_name)
    basename = path.name[:-3] if path.name.endswith(".py") else path.name
    runs = load_test_runs(module, name=f"{package_name}.{basename}.launch_tests")
    with _log_root(log_dir) as root:
        for index, run in enumerate(runs):
            run.source = str(path)  # type: ignore[attr-defined]
            if len(runs) > 1:
                print(f"\nStarting test run {run}", file=stdout)
            run_dir = root / (f"run{index}" if len(runs) > 1 else "run")
            bus = isolated_bus() if isolate else contextlib.nullcontext()
            with bus as where:
                if where is not None:
                    print(f"Running with ROS_DOMAIN_ID {where.domain_id} on the router {where.endpoint}",
                          file=stdout)
                kept = None
                if artifacts is not None:
                    from diffctl.testing.artifacts import Artifacts

                    label = re.sub(r"[^\w.=-]+", "_", str(run))
                    target = artifacts / label if len(runs) > 1 else artifacts
                    kept = Artifacts(target, root / f"artifacts-work-{index}")
                one: RunResult | None = None
                try:
                    one = run_once(run, arguments, log_dir=run_dir, stdout=stdout, stderr=stderr,
                                   on_failure=kept.on_failure if kept is not None else None)
                finally:
                    if kept is not None:
                        failed = one is None or not one.ok
                        kept.finish(failed, one.logs if one is not None else read_logs(run_dir))
                        if failed:
                            print(f"artifacts of {run}: {kept.target}", file=stdout)
            file_result.runs.append(one)
            if one.failed_early:
                break  # as launch_testing: the runs after a launch that died are not attempted
    return file_result


def cases_of(file_result: FileResult) -> Iterator[tuple[RunResult, unittest.TestCase]]:
    for one in file_result.runs:
        for case in iterate_cases(one.run.pre_shutdown_tests):
            yield one, case
        for case in iterate_cases(one.run.post_shutdown_tests):
            yield one, case


def env_flag(name: str) -> bool:
    return os.environ.get(name, "") not in ("", "0", "false")
