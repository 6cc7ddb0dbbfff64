"""launch_testing_ros' pytest plugin (entry point `launch_ros`): launch test files whose
generate_test_description is marked `@pytest.mark.rostest` are collected by LaunchROSTestModule."""

from __future__ import annotations

from typing import Any

import pytest


def pytest_launch_collect_makemodule(path: Any, parent: Any, entrypoint: Any) -> Any:
    marks = getattr(entrypoint, "pytestmark", [])
    if not any(m.name == "rostest" for m in marks):
        return None
    from .pytest.hooks import LaunchROSTestModule

    module = LaunchROSTestModule.from_parent(parent, path=path)
    for mark in marks:
        module.add_marker(getattr(pytest.mark, mark.name).with_args(*mark.args, **mark.kwargs))
    return module


def pytest_configure(config: Any) -> None:
    config.addinivalue_line(
        "markers", "rostest: mark a generate_test_description function as a ROS launch test entrypoint"
    )
