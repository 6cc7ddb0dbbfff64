"""A launch test as ros2/launch's examples write them: a counting process, output in order, exit codes."""

import os
import sys
import unittest

import launch.actions
import launch_testing
import launch_testing.actions
import pytest
from launch_testing.asserts import assertSequentialStdout

import launch

HERE = os.path.dirname(os.path.abspath(__file__))


@pytest.mark.launch_test
def generate_test_description():
    dut_process = launch.actions.ExecuteProcess(
        cmd=[sys.executable, os.path.join(HERE, "counter.py")],
        additional_env={"PYTHONUNBUFFERED": "1"},
        output="screen",
    )
    return launch.LaunchDescription([dut_process, launch_testing.actions.ReadyToTest()]), {"dut_process": dut_process}


class TestGoodProcess(unittest.TestCase):
    def test_count_to_four(self, proc_output):
        for n in range(1, 5):
            proc_output.assertWaitFor(f"Loop {n}", timeout=10, stream="stdout")


@launch_testing.post_shutdown_test()
class TestProcessOutput(unittest.TestCase):
    def test_exit_code(self, proc_info):
        launch_testing.asserts.assertExitCodes(proc_info)

    def test_full_output(self, proc_output, dut_process):
        with assertSequentialStdout(proc_output, dut_process) as cm:
            cm.assertInStdout("Starting Up")
            for n in range(4):
                cm.assertInStdout(f"Loop {n}")
            cm.assertInStdout("Shutting Down")

    def test_out_of_order(self, proc_output, dut_process):
        with self.assertRaisesRegex(AssertionError, "'Loop 2' not found"):  # noqa: SIM117 (as upstream writes it)
            with assertSequentialStdout(proc_output, dut_process) as cm:
                cm.assertInStdout("Loop 1")
                cm.assertInStdout("Loop 3")
                cm.assertInStdout("Loop 2")
