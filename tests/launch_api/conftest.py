"""Tests of diffctl's launch core used as ros2/launch's API: from scripts, with real child processes.

They import `diffctl.launch` itself: in one pytest process the legacy engine's tests may have bound the ROS
name `launch` to the legacy mapping. The ROS names are checked in subprocesses (test_packaging.py).
"""

from __future__ import annotations

import logging
from collections.abc import Iterator

import pytest


@pytest.fixture(autouse=True)
def launch_logging() -> Iterator[None]:
    """launch's logging bound to this test's captured stdout; the standard logger class back afterwards."""
    import diffctl.launch.logging as launch_logging

    logger_class = logging.getLoggerClass()
    launch_logging.reset()
    yield
    launch_logging.reset()
    logging.setLoggerClass(logger_class if logger_class is not launch_logging.LaunchLogger else logging.Logger)
