"""Module parity of launch_testing, launch_testing_ros and launch_pytest with Jazzy's: every public module and name
of ros2/launch and ros2/launch_ros (branch jazzy; `__all__`, else the module's top-level definitions) imports, as
diffctl's own modules. The names were written down from the upstream sources; the programmatic API launch_test
itself uses runs a real test."""

from __future__ import annotations

import importlib
import subprocess
import sys
from pathlib import Path

# module → its public names in Jazzy (launch 3.4 / launch_ros 0.26 sources)
JAZZY = {
    "launch_testing": (
        "tools parametrize post_shutdown_test ready_to_test_action_timeout ActiveIoHandler "
        "ActiveProcInfoHandler IoHandler ProcInfoHandler ReadyAggregator"
    ),
    "launch_testing.actions": "GTest PyTest ReadyToTest",
    "launch_testing.actions.gtest": "GTest",
    "launch_testing.actions.pytest": "PyTest",
    "launch_testing.actions.ready": "ReadyToTest",
    "launch_testing.actions.test": "Test",
    "launch_testing.asserts": (
        "assertDefaultStream assertExitCodes assertInStderr assertInStdout assertInStream "
        "assertSequentialStdout SequentialTextChecker NO_CMD_ARGS EXIT_OK EXIT_SIGINT EXIT_SIGKILL "
        "EXIT_SIGQUIT EXIT_SIGSEGV"
    ),
    "launch_testing.asserts.assert_exit_codes": (
        "EXIT_OK EXIT_SIGINT EXIT_SIGQUIT EXIT_SIGKILL EXIT_SIGSEGV EXIT_FORCED assertExitCodes"
    ),
    "launch_testing.asserts.assert_output": "assertInStream assertInStdout assertInStderr assertDefaultStream",
    "launch_testing.asserts.assert_sequential_output": "SequentialTextChecker assertSequentialStdout",
    "launch_testing.decorator": "post_shutdown_test",
    "launch_testing.event_handlers": "StdoutReadyListener",
    "launch_testing.event_handlers.stdout_ready_listener": "StdoutReadyListener",
    "launch_testing.io_handler": "IoHandler ActiveIoHandler",
    "launch_testing.junitxml": "unittestResultsToXml unittestResultToXml unittestCaseToXml",
    "launch_testing.launch_test": "add_arguments parse_arguments run main",
    "launch_testing.legacy": "LaunchTestService output",  # its __all__ also lists 'actions', which it lacks
    "launch_testing.legacy.output": (
        "get_default_filtered_prefixes get_default_filtered_patterns get_rmw_output_filter "
        "create_output_lines_filter create_output_lines_test create_output_regex_test "
        "create_output_test_from_file"
    ),
    "launch_testing.loader": (
        "slim_formatwarning TestRun LoadTestsFromPythonModule PreShutdownTestLoader PostShutdownTestLoader"
    ),
    "launch_testing.markers": "keep_alive retry_on_failure",
    "launch_testing.parametrize": "parametrize",
    "launch_testing.parse_arguments": "parse_launch_arguments",
    "launch_testing.print_arguments": "print_arguments_of_launch_description",
    "launch_testing.proc_info_handler": "ProcInfoHandler ActiveProcInfoHandler",
    "launch_testing.pytest": "",
    "launch_testing.pytest.hooks": (
        "LaunchTestFailure LaunchTestFailureRepr LaunchTestItem LaunchTestModule find_launch_test_entrypoint "
        "pytest_pycollect_makemodule pytest_launch_collect_makemodule pytest_addhooks pytest_addoption "
        "pytest_configure"
    ),
    "launch_testing.pytest.hookspecs": "pytest_launch_collect_makemodule",
    "launch_testing.ready_aggregator": "ReadyAggregator",
    "launch_testing.ready_to_test_action_timeout": "ready_to_test_action_timeout",
    "launch_testing.test_result": "FailResult SkipResult TestResult",
    "launch_testing.test_runner": "LaunchTestRunner",
    "launch_testing.tools": "basic_output_filter expect_output expected_output_from_file launch_process ProcessProxy",
    "launch_testing.tools.output": (
        "get_default_filtered_prefixes get_default_filtered_patterns basic_output_filter "
        "expected_output_from_file expect_output"
    ),
    "launch_testing.tools.process": "ProcessProxy launch_process",
    "launch_testing.tools.text": "normalize_lineseps build_line_match build_text_match",
    "launch_testing.util": "resolveProcesses KeepAliveProc NoMatchingProcessException NO_CMD_ARGS",
    "launch_testing.util.proc_lookup": "NO_CMD_ARGS NoMatchingProcessException resolveProcesses",
    "launch_pytest": "actions fixture tools",
    "launch_pytest.actions": "ReadyToTest",
    "launch_pytest.fixture": (
        "finalize_launch_service get_launch_service_fixture get_launch_context_fixture get_event_loop_fixture "
        "fixture"
    ),
    "launch_pytest.plugin": (
        "LaunchTestWarning pytest_configure iterate_ready_to_test_actions get_ready_to_test_action "
        "pytest_fixture_setup is_launch_test is_launch_test_mark_valid has_shutdown_kwarg "
        "get_launch_test_fixture get_launch_test_fixturename is_valid_test_item need_shutdown_test_item "
        "generate_test_items from_parent pytest_pycollect_makeitem is_shutdown_test "
        "is_same_launch_test_fixture pytest_collection_modifyitems pytest_pyfunc_call run_until_complete "
        "wrap_coroutine wrap_func wrap_generator wrap_generator_fscope wrap_asyncgen wrap_asyncgen_fscope "
        "launch_service launch_context event_loop"
    ),
    "launch_pytest.tools": (
        "assert_output assert_output_sync assert_stderr assert_stderr_sync process wait_for_exit "
        "wait_for_exit_sync wait_for_output wait_for_output_sync wait_for_start wait_for_start_sync "
        "wait_for_stderr wait_for_stderr_sync"
    ),
    "launch_pytest.tools.process": (
        "register_event_handler wait_for_output assert_output wait_for_output_sync assert_output_sync "
        "wait_for_stderr assert_stderr wait_for_stderr_sync assert_stderr_sync wait_for_start "
        "wait_for_start_sync wait_for_exit wait_for_exit_sync"
    ),
    "launch_testing_ros": "DataRepublisher LaunchTestRunner MessagePump tools WaitForTopics",
    "launch_testing_ros.data_republisher": "DataRepublisher",
    "launch_testing_ros.message_pump": "MessagePump",
    "launch_testing_ros.pytest": "",
    "launch_testing_ros.pytest.hooks": "LaunchROSTestItem LaunchROSTestModule",
    "launch_testing_ros.test_runner": "LaunchTestRunner",
    "launch_testing_ros.tools": "basic_output_filter",
    "launch_testing_ros.tools.output": "get_rmw_output_filter basic_output_filter",
    "launch_testing_ros.wait_for_topics": "WaitForTopics",
}



def test_every_jazzy_module_and_name_is_provided() -> None:
    missing = []
    for module, names in JAZZY.items():
        try:
            mod = importlib.import_module(module)
        except ImportError as e:
            missing.append(f"{module}: {e}")
            continue
        assert "diffctl" in (mod.__file__ or ""), f"{module} is not diffctl's: {mod.__file__}"
        missing += [f"{module}.{n}" for n in names.split() if not hasattr(mod, n)]
    assert not missing, missing


LAUNCH_TEST_API = """\
import importlib.util, sys
from launch_testing.junitxml import unittestResultsToXml
from launch_testing.loader import LoadTestsFromPythonModule
from launch_testing.test_runner import LaunchTestRunner
spec = importlib.util.spec_from_file_location("probe_launch_test", sys.argv[1])
module = importlib.util.module_from_spec(spec)
spec.loader.exec_module(module)
runner = LaunchTestRunner(LoadTestsFromPythonModule(module, name="probe.launch_tests"), launch_file_arguments=[])
runner.validate()
results = runner.run()
tree = unittestResultsToXml(name="probe", test_results=results)
root = tree.getroot()
print("RESULT", all(r.wasSuccessful() for r in results.values()), root.get("tests"), root.get("failures"))
"""


def test_launch_test_programmatic_api(tmp_path: Path) -> None:
    """launch_test's own main, written against launch_testing's API: loader, runner, results, JUnit XML."""
    here = Path(__file__).parent / "launch_tests"
    script = tmp_path / "api.py"
    script.write_text(LAUNCH_TEST_API)
    for name, expect in (("good_proc_launch_test.py", "RESULT True"), ("bad_proc_launch_test.py", "RESULT False")):
        r = subprocess.run([sys.executable, str(script), str(here / name)], capture_output=True, text=True,
                           timeout=90, cwd=here, start_new_session=True)
        assert expect in r.stdout, r.stdout + r.stderr


def test_ready_aggregator_and_stdout_ready_listener() -> None:
    from launch.actions import ExecuteProcess
    from launch.event_handlers import OnProcessIO
    from launch.events.process import ProcessStdout
    from launch_testing import ReadyAggregator
    from launch_testing.event_handlers import StdoutReadyListener

    from launch import LaunchContext

    fired = []
    agg = ReadyAggregator(lambda: fired.append(1), 2)
    agg.ready_fn()
    assert not fired
    agg.ready_fn()
    assert fired == [1]
    proc = ExecuteProcess(cmd=["true"], name="p")
    go = ExecuteProcess(cmd=["true"], name="go")
    listener = StdoutReadyListener(target_action=proc, ready_txt="ready", actions=[go])
    assert isinstance(listener, OnProcessIO) and listener.describe()[1] == [go]

    def said(text: bytes) -> ProcessStdout:
        return ProcessStdout(text=text, action=proc, name="p", cmd=["true"], cwd=None, env=None, pid=1)

    assert listener.matches(said(b"all ready now"))
    assert listener.handle(said(b"all ready now"), LaunchContext()) == [go]
    assert listener.handle(said(b"not yet"), LaunchContext()) is None
