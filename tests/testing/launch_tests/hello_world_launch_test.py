"""keep_alive: the launch stays up after its only process (a shell's echo) has exited."""

import unittest

import launch.actions
import launch_testing.actions
import launch_testing.asserts
import launch_testing.markers
import pytest

import launch


@pytest.mark.launch_test
@launch_testing.markers.keep_alive
def generate_test_description():
    return launch.LaunchDescription([
        launch.actions.ExecuteProcess(cmd=["echo", "hello_world"], shell=True),
        launch_testing.actions.ReadyToTest(),
    ])


class TestHelloWorldProcess(unittest.TestCase):
    def test_read_stdout(self, proc_output):
        proc_output.assertWaitFor("hello_world", timeout=10, stream="stdout")


@launch_testing.post_shutdown_test()
class TestHelloWorldShutdown(unittest.TestCase):
    def test_exit_codes(self, proc_info):
        launch_testing.asserts.assertExitCodes(proc_info)
