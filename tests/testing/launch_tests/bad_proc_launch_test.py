"""Failures where launch_test fails: a process exiting 1 checked with assertExitCodes, output that never comes,
and a wrong expectation after shutdown."""

import os
import sys
import unittest

import launch_testing
import launch_testing.actions
import launch_testing.asserts
import launch_testing.util
import pytest

import launch

HERE = os.path.dirname(os.path.abspath(__file__))


@pytest.mark.launch_test
def generate_test_description():
    bad = launch.actions.ExecuteProcess(cmd=[sys.executable, os.path.join(HERE, "exit_code_proc.py")], name="bad")
    return launch.LaunchDescription(
        [bad, launch_testing.util.KeepAliveProc(), launch_testing.actions.ReadyToTest()]
    ), {"bad": bad}


class TestBad(unittest.TestCase):
    def test_bad_exits(self, proc_info, bad):
        proc_info.assertWaitForShutdown(process=bad, timeout=10)

    def test_never_printed(self, proc_output, bad):
        proc_output.assertWaitFor("never printed", process=bad, timeout=0.5, stream="stdout")


@launch_testing.post_shutdown_test()
class TestAfter(unittest.TestCase):
    def test_exit_codes(self, proc_info):
        launch_testing.asserts.assertExitCodes(proc_info)

    def test_bad_exit_code_is_one(self, proc_info, bad):
        launch_testing.asserts.assertExitCodes(proc_info, [1], process=bad)

    def test_stdout(self, proc_output, bad):
        launch_testing.asserts.assertInStdout(proc_output, "Exiting with a code", bad)
