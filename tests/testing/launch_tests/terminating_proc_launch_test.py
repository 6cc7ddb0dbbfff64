"""launch_testing's example processes found as its examples find them (the package prefix of launch_testing),
started from the tests themselves with launch_testing.tools.launch_process."""

import os
import sys
import unittest

import ament_index_python
import launch.actions
import launch_testing
import launch_testing.actions
import launch_testing.asserts
import launch_testing.markers
import launch_testing.tools
import pytest

import launch


def proc(*args):
    path = os.path.join(ament_index_python.get_package_prefix("launch_testing"), "lib/launch_testing",
                        "terminating_proc.py")
    return launch.actions.ExecuteProcess(cmd=[sys.executable, path, *args], name="terminating_proc.py",
                                         additional_env={"PYTHONUNBUFFERED": "1"}, output="screen")


@pytest.mark.launch_test
@launch_testing.markers.keep_alive
def generate_test_description():
    return launch.LaunchDescription([launch_testing.actions.ReadyToTest()])


class TestTerminatingProc(unittest.TestCase):
    def test_with_args(self, launch_service, proc_info, proc_output):
        action = proc("--foo", "bar")
        with launch_testing.tools.launch_process(launch_service, action, proc_info, proc_output):
            proc_info.assertWaitForStartup(process=action, timeout=2)
            proc_output.assertWaitFor("Starting Up", process=action, timeout=2, stream="stdout")
            proc_output.assertWaitFor("Called with arguments ['--foo', 'bar']", process=action, timeout=2,
                                      stream="stdout")
            proc_output.assertWaitFor("Done", process=action, timeout=3, stream="stdout")
            proc_info.assertWaitForShutdown(process=action, timeout=4)
        launch_testing.asserts.assertExitCodes(proc_info, process=action)

    def test_unhandled_exception(self, launch_service, proc_info, proc_output):
        action = proc("--exception")
        with launch_testing.tools.launch_process(launch_service, action, proc_info, proc_output):
            proc_info.assertWaitForStartup(process=action, timeout=2)
            proc_output.assertWaitFor("Process had a pretend error", process=action, timeout=4)  # stderr
            proc_info.assertWaitForShutdown(process=action, timeout=4)
        launch_testing.asserts.assertExitCodes(proc_info, process=action, allowable_exit_codes=[1])
