"""launch_testing's and launch_pytest's API where diffctl's earlier versions went wrong (issue 29): process lookup
that finds nothing, sequential-output failures, parametrize's partial binding, the framework `diffctl test`
picks for a file, and the `launch_test` command. No process is started here: the events are launch's own
classes, made as the launch makes them."""

from __future__ import annotations

import importlib.metadata
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import launch_testing
import pytest
from launch.actions import ExecuteProcess
from launch.events.process import ProcessStarted, ProcessStdout
from launch_testing.asserts import assertSequentialStdout
from launch_testing.io_handler import ActiveIoHandler, IoHandler
from launch_testing.util import NoMatchingProcessException, resolveProcesses

from diffctl.testing.discovery import framework
from launch import LaunchContext


def _started(name: str) -> tuple[ExecuteProcess, dict]:
    """An ExecuteProcess as launch has it when its process starts: prepared, its details (name-N) known."""
    action = ExecuteProcess(cmd=["talker", "--fast"], name=name)
    action.prepare(LaunchContext())
    return action, {"action": action, **action.process_details, "pid": 4242}


def test_no_process_is_no_matching_process_not_an_index_error() -> None:
    empty = IoHandler()
    with pytest.raises(NoMatchingProcessException, match="No data recorded for any process"):
        resolveProcesses(empty)
    with pytest.raises(NoMatchingProcessException, match="talker"):
        resolveProcesses(empty, process="talker")
    with pytest.raises(NoMatchingProcessException), assertSequentialStdout(empty, "talker"):
        pass
    action = ExecuteProcess(cmd=["talker", "--fast"], name="talker")  # not started: launch_testing names its command
    with pytest.raises(NoMatchingProcessException, match="talker --fast"):
        resolveProcesses(empty, process=action)


def test_sequential_output_failure_shows_the_output_around_the_last_match() -> None:
    _, details = _started("talker")
    proc_output = ActiveIoHandler()
    proc_output.track(details["name"])
    for line in ("Publishing: 'hello 1'\n", "Publishing: 'hello 2'\n", "Publishing: 'hello 3'\n"):
        proc_output.append(ProcessStdout(text=line.encode(), **details))
    with pytest.raises(AssertionError) as failure, assertSequentialStdout(proc_output, "talker") as cm:
        cm.assertInStdout("hello 2")
        cm.assertInStdout("hello 1")  # printed, but before 'hello 2'
    message = str(failure.value)
    assert "'hello 1' not found in sequence after previous match" in message
    assert "Publishing: 'hello 2'" in message and "Publishing: 'hello 3'" in message


def test_parametrize_binds_its_names_and_leaves_the_others_to_the_caller() -> None:
    calls = []

    @launch_testing.parametrize("speed, wheel", [(1, "left"), (2, "right")])
    def generate_test_description(speed, wheel, world):
        calls.append((speed, wheel, world))

    runs = list(generate_test_description())
    assert [params for _, params in runs] == [{"speed": 1, "wheel": "left"}, {"speed": 2, "wheel": "right"}]
    for index, (function, _) in enumerate(runs):
        function(world=f"w{index}")
    assert calls == [(1, "left", "w0"), (2, "right", "w1")]


def test_process_started_events_name_the_process_as_launch_does() -> None:
    action, details = _started("talker")
    info = launch_testing.ProcInfoHandler()
    info.append(ProcessStarted(**details))
    assert resolveProcesses(info, process="talker") == [action]
    assert info["talker"].process_name == details["name"]
    assert re.fullmatch(r"talker-\d+", details["name"])  # launch numbers the processes of one name


FILES = {
    # launch_pytest whose fixture happens to be called generate_test_description: pytest's, not launch_test's
    "test_pytest_style.py": """
        import launch
        import launch_pytest
        import pytest

        @launch_pytest.fixture
        def generate_test_description():
            return launch.LaunchDescription([])

        @pytest.mark.launch(fixture=generate_test_description)
        def test_runs():
            pass
        """,
    "test_unittest_style.launch.py": """
        import unittest
        import launch
        import launch_testing.actions

        def generate_test_description():
            return launch.LaunchDescription([launch_testing.actions.ReadyToTest()])

        class TestIt(unittest.TestCase):
            def test_it(self):
                pass
        """,
    "test_plain.py": "def test_plain():\n    pass\n",
    "helper.py": "VALUE = 1\n",
    "test_broken_launch_test.py": "def generate_test_description(:\n    pass\n",
}


def test_diffctl_test_picks_the_framework_by_what_a_file_uses(tmp_path: Path) -> None:
    for name, text in FILES.items():
        (tmp_path / name).write_text(textwrap.dedent(text))
    kinds = {name: framework(tmp_path / name) for name in FILES}
    assert kinds == {
        "test_pytest_style.py": "launch_pytest",
        "test_unittest_style.launch.py": "launch",
        "test_plain.py": "pytest",
        "helper.py": None,
        "test_broken_launch_test.py": "launch",  # launch_test reports its syntax error
    }


def test_launch_test_command_is_installed() -> None:
    (script,) = [e for e in importlib.metadata.entry_points(group="console_scripts") if e.name == "launch_test"]
    assert script.value == "diffctl.testing.launch_test:main"
    r = subprocess.run([str(Path(sys.executable).parent / "launch_test"), "--help"], capture_output=True, text=True,
                       timeout=60)
    assert r.returncode == 0 and "launch_test_file" in r.stdout and "--junit-xml" in r.stdout
