"""A launch_pytest test that hangs in its body, its launch running a process that ignores SIGINT and SIGTERM."""

import os
import time

import launch_pytest
import pytest

import launch


@launch_pytest.fixture
def stubborn():
    marker = os.environ.get("HANG_MARKER", "4242.5")
    return launch.LaunchDescription([
        launch.actions.ExecuteProcess(cmd=["sh", "-c", f"trap '' INT TERM; sleep {marker} & sleep {marker}; wait"]),
    ])


@pytest.mark.launch(fixture=stubborn)
def test_hangs():
    time.sleep(600)
