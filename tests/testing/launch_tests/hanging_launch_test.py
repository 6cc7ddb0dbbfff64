"""A test that hangs, with a process that ignores SIGINT and a grandchild: stopped at diffctl test's timeout."""

import os
import sys
import time
import unittest

import launch.actions
import launch_testing.actions
import pytest

import launch


@pytest.mark.launch_test
def generate_test_description():
    marker = os.environ.get("HANG_MARKER", "4242.5")
    stubborn = launch.actions.ExecuteProcess(
        cmd=["sh", "-c", f"trap '' INT TERM; sleep {marker} & sleep {marker}; wait"], name="stubborn"
    )
    return launch.LaunchDescription([stubborn, launch_testing.actions.ReadyToTest()])


class TestHangs(unittest.TestCase):
    def test_hangs(self):
        print("hanging", file=sys.stderr, flush=True)
        time.sleep(600)
