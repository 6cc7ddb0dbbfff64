"""Parametrized runs, arguments handed on by name, launch arguments, a process launched from a test."""

import os
import sys
import unittest

import launch.actions
import launch.substitutions
import launch_testing
import launch_testing.actions
import launch_testing.markers
import launch_testing.tools
import launch_testing.util
import pytest

import launch

HERE = os.path.dirname(os.path.abspath(__file__))


@pytest.mark.launch_test
@launch_testing.parametrize("arg_param", ["thing=On", "thing=Off", "flag1"])
def generate_test_description(arg_param):
    dut = launch.actions.ExecuteProcess(
        cmd=[sys.executable, os.path.join(HERE, "terminating.py"), f"--{arg_param}",
             launch.substitutions.LaunchConfiguration("dut_arg")],
    )
    return launch.LaunchDescription([
        launch.actions.DeclareLaunchArgument("dut_arg", default_value="default", description="passed on"),
        dut,
        launch_testing.util.KeepAliveProc(),
        launch_testing.actions.ReadyToTest(),
    ]), {"dut_process": dut, "int_val": 10}


class TestProcessOutput(unittest.TestCase):
    def test_process_outputs_expected_value(self, proc_output, arg_param):
        proc_output.assertWaitFor("--" + arg_param, timeout=10, stream="stdout")

    def test_terminates(self, proc_info, dut_process, int_val):
        self.assertEqual(int_val, 10)
        proc_info.assertWaitForShutdown(process=dut_process, timeout=10)

    def test_launched_from_test(self, launch_service, proc_info, proc_output):
        action = launch.actions.ExecuteProcess(
            cmd=[sys.executable, os.path.join(HERE, "terminating.py"), "--foo", "bar"], name="from_test"
        )
        with launch_testing.tools.launch_process(launch_service, action, proc_info, proc_output) as proxy:
            proc_info.assertWaitForStartup(process=action, timeout=5)
            proc_output.assertWaitFor("Called with arguments ['--foo', 'bar']", process=action, timeout=5,
                                      stream="stdout")
            proc_info.assertWaitForShutdown(process=action, timeout=5)
            self.assertEqual(proxy.exit_code, 0)
        launch_testing.asserts.assertExitCodes(proc_info, process=action)


@launch_testing.post_shutdown_test()
class TestAfter(unittest.TestCase):
    def test_arg_in_cmd(self, dut_process, test_args):
        self.assertIn(test_args.get("dut_arg", "default"), dut_process.process_details["cmd"])

    def test_dut_exit_code(self, proc_info, dut_process):
        launch_testing.asserts.assertExitCodes(proc_info, process=dut_process)
