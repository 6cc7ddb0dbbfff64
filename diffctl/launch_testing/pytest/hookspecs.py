"""The hook other plugins implement to make the collector of a launch test file (launch_testing_ros does)."""

from __future__ import annotations

from typing import Any

import pytest


@pytest.hookspec(firstresult=True)
def pytest_launch_collect_makemodule(path: Any, parent: Any, entrypoint: Any) -> Any:
    """A collector for the launch test file at `path`, whose generate_test_description is `entrypoint`, or
    None to leave it to the next plugin."""
