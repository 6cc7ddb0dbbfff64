"""LaunchTestRunner: each TestRun launched in turn, its active tests run while the launch does, its
post-shutdown tests after.

The launch runs on the calling thread (LaunchService.run takes the main thread's signals); the active tests
run on a thread of their own that waits for the ReadyToTest, then ends the launch when they are done. A
launch that ends first (its processes all exited, Ctrl-C) fails the run's tests and stops the runner.
"""

from __future__ import annotations

import contextlib
import inspect
import threading
import unittest
from typing import Any

from diffctl.launch import LaunchDescription, LaunchDescriptionSource, LaunchService
from diffctl.launch.actions import IncludeLaunchDescription, RegisterEventHandler
from diffctl.launch.event_handlers import OnProcessExit, OnProcessIO, OnProcessStart

from .io_handler import ActiveIoHandler
from .parse_arguments import parse_launch_arguments
from .proc_info_handler import ActiveProcInfoHandler
from .test_result import FailResult, SkipResult, TestResult


class _LaunchDiedException(Exception):
    """The launch of a run ended before its active tests did."""


class _RunnerWorker:
    """One TestRun: its launch, its two batches of tests, their combined result."""

    def __init__(self, test_run: Any, test_run_preamble: list[Any], launch_file_arguments: Any = (),
                 debug: bool = False, result_class: type = TestResult, launch_service: Any = None) -> None:
        self._test_run = test_run
        self._test_run_preamble = list(test_run_preamble)
        self._launch_file_arguments = list(launch_file_arguments)
        self._launch_service = launch_service if launch_service is not None else LaunchService(debug=debug)
        self._result_class = result_class
        self._processes_launched = threading.Event()
        self._tests_completed = threading.Event()
        self._launch_ended = threading.Event()
        self._results: Any = None
        self.timeout = test_run.timeout
        self.proc_info = ActiveProcInfoHandler()
        self.proc_output = ActiveIoHandler()
        self._test_tr = threading.Thread(target=self._run_test, name="test_runner_thread", daemon=True)

    def run(self) -> Any:
        run = self._test_run
        test_ld, test_values = run.normalized_test_description(ready_fn=self._processes_launched.set)
        proc_info, proc_output = self.proc_info, self.proc_output
        arguments = parse_launch_arguments(self._launch_file_arguments)
        test_args = dict(arguments)
        values = dict(test_values, **run.param_args)
        active = {"launch_service": self._launch_service, "proc_info": proc_info, "proc_output": proc_output,
                  "test_args": test_args}
        run.bind(run.pre_shutdown_tests, injected_attributes=active, injected_args=dict(values, **active))
        # after shutdown, the records themselves: nothing to wait for any more
        done = {"proc_info": proc_info._proc_info_handler, "proc_output": proc_output._io_handler,
                "test_args": test_args}
        run.bind(run.post_shutdown_tests, injected_attributes=done, injected_args=dict(values, **done))
        self._launch_service.include_launch_description(LaunchDescription([
            *self._test_run_preamble,
            RegisterEventHandler(OnProcessStart(on_start=lambda event, context: proc_info.append(event))),
            RegisterEventHandler(OnProcessStart(on_start=lambda event, context: proc_output.track(event.process_name))),
            RegisterEventHandler(OnProcessExit(on_exit=lambda event, context: proc_info.append(event))),
            RegisterEventHandler(OnProcessIO(on_stdout=proc_output.append, on_stderr=proc_output.append)),
            IncludeLaunchDescription(LaunchDescriptionSource(launch_description=test_ld), launch_arguments=arguments),
        ]))
        self._test_tr.start()
        try:
            self._launch_service.run(shutdown_when_idle=not run.markers.get("keep_alive", False))
        finally:
            self._launch_ended.set()
        if not self._tests_completed.is_set():
            print("Processes under test stopped before tests completed")
            self._print_process_output_summary(proc_info, proc_output)
            raise _LaunchDiedException()
        after = unittest.TextTestRunner(verbosity=2, resultclass=self._result_class).run(run.post_shutdown_tests)
        self._results.append(after)
        return self._results

    def _wait_until_ready(self) -> bool:
        """Wait for the ReadyToTest, no longer than the run's timeout nor than the launch lasts."""
        waited = 0.0
        while waited < self.timeout:
            step = min(0.1, self.timeout - waited)
            if self._processes_launched.wait(step):
                return True
            if self._launch_ended.is_set():
                return self._processes_launched.is_set()
            waited += step
        return self._processes_launched.is_set()

    def _run_test(self) -> None:
        if not self._wait_until_ready():
            if not self._launch_ended.is_set():
                print("Timed out waiting for processes to start up")
            self._launch_service.shutdown()
            return
        try:
            runner = unittest.TextTestRunner(verbosity=2, resultclass=self._result_class)
            self._results = runner.run(self._test_run.pre_shutdown_tests)
        finally:
            self._tests_completed.set()
            self._launch_service.shutdown()

    @staticmethod
    def _print_process_output_summary(proc_info: Any, proc_output: Any) -> None:
        """The output of every process that ended badly: why the launch died, most often."""
        for event in proc_info:
            if getattr(event, "returncode", 0) == 0:
                continue
            name = event.process_name
            print(f"Process '{name}' exited with {event.returncode}")
            print(f"##### '{name}' output #####")
            with contextlib.suppress(KeyError):
                for io in proc_output[event.action]:
                    print(io.text.decode(errors="replace"))
            print("#" * (len(name) + 21))


class LaunchTestRunner:
    """Runs TestRuns (loader.LoadTestsFromPythonModule) one after the other and answers {run: result}."""

    def __init__(self, test_runs: list[Any], launch_file_arguments: Any = (), debug: bool = False) -> None:
        self._test_runs = test_runs
        self._launch_file_arguments = launch_file_arguments
        self._debug = debug

    def generate_preamble(self) -> list[Any]:
        """Entities included before each run's test description (none here; a subclass may add some)."""
        return []

    def _run_scope(self, test_run: Any) -> contextlib.AbstractContextManager[Any]:
        """What each run happens within (diffctl's runner: a bus of its own)."""
        return contextlib.nullcontext()

    def _new_worker(self, test_run: Any) -> _RunnerWorker:
        return _RunnerWorker(test_run, self.generate_preamble(), self._launch_file_arguments, self._debug)

    def _run_one(self, test_run: Any) -> Any:
        with self._run_scope(test_run):
            return self._new_worker(test_run).run()

    def run(self) -> dict[Any, Any]:
        results: dict[Any, Any] = {}
        for test_run in self._test_runs:
            if len(self._test_runs) > 1:
                print(f"\nStarting test run {test_run}")
            try:
                results[test_run] = self._run_one(test_run)
            except unittest.case.SkipTest as skip:  # generate_test_description is skipped
                print(f"{test_run} is skipped: {skip}")
                results[test_run] = SkipResult(test_run=test_run, skip_reason=str(skip))
            except _LaunchDiedException:  # most likely Ctrl-C: the runs after it are not attempted
                results[test_run] = FailResult(test_run=test_run,
                                               message="Launch stopped before the active tests finished.")
                break
        return results

    def validate(self) -> None:
        """Refuse, before anything starts, a generate_test_description whose arguments and parametrization
        disagree."""
        for test_run in self._test_runs:
            spec = inspect.getfullargspec(inspect.unwrap(test_run._test_description_function))
            accepted = spec.args + spec.kwonlyargs
            for name in test_run.param_args:
                if name not in accepted:
                    raise Exception("Could not find an argument in generate_test_description matching "
                                    f"prametrized argument '{name}'")
            for name in accepted:
                if name not in test_run.param_args:
                    raise Exception(f"generate_test_description has unexpected extra argument '{name}'")
            signature = inspect.signature(test_run._test_description_function, follow_wrapped=False)
            try:
                signature.bind(ready_fn=lambda: None)
            except TypeError:
                signature.bind()


