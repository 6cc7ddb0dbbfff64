"""A launch that ends before its tests: the only process exits, nothing keeps the launch alive (launch_test
then fails every test with 'Launch stopped before the active tests finished.')."""

import unittest

import launch_testing.actions
import pytest

import launch


@pytest.mark.launch_test
def generate_test_description():
    return launch.LaunchDescription([
        launch.actions.ExecuteProcess(cmd=["sh", "-c", "echo hello_world; exit 3"], name="short"),
        launch_testing.actions.ReadyToTest(),
    ])


class TestWaits(unittest.TestCase):
    def test_waits_long(self, proc_output):
        proc_output.assertWaitFor("not coming", timeout=10, stream="stdout")
