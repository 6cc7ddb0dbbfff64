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
    echo = launch.actions.ExecuteProcess(cmd=["echo", "hello_world"], shell=True)
    return launch.LaunchDescription([echo, launch_testing.actions.ReadyToTest()]), {"echo": echo}


class TestHelloWorldProcess(unittest.TestCase):
    def test_read_stdout(self, proc_output, proc_info, echo):
        proc_output.assertWaitFor("hello_world", timeout=10, stream="stdout")
        # The launch is shut down as soon as the active tests end, and a process still running then is sent
        # SIGINT: the exit code checked after shutdown is echo's own only once its exit has been seen here.
        # Having printed is not having exited (ros2/launch#534: upstream's example races the same way).
        proc_info.assertWaitForShutdown(process=echo, timeout=10)


@launch_testing.post_shutdown_test()
class TestHelloWorldShutdown(unittest.TestCase):
    def test_exit_codes(self, proc_info):
        launch_testing.asserts.assertExitCodes(proc_info)
