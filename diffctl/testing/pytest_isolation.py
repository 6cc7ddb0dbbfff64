"""pytest plugin (entry point `diffctl_test_isolation`): a session that runs launch tests (launch_testing
files, launch_pytest tests) runs them on a Zenoh router and ROS domain of its own, so a pytest run in CI
neither hears nor disturbs other tests and robots on the machine.

The bus is started once the session knows it has launch tests and stopped when it ends; a session that
`diffctl test` already isolated (DIFFCTL_TEST_ISOLATED) is left as it is, as is one with no launch test.
"""

from __future__ import annotations

import os
from typing import Any

ISOLATED_ENV = "DIFFCTL_TEST_ISOLATED"
_OPEN: dict[int, Any] = {}  # id(session) → the isolated_bus context it entered


def _is_launch_test(item: Any) -> bool:
    if item.get_closest_marker("launch") is not None:
        return True
    from diffctl.launch_testing.pytest.hooks import LaunchTestItem

    return isinstance(item, LaunchTestItem)


def pytest_collection_finish(session: Any) -> None:
    if os.environ.get(ISOLATED_ENV) or not any(_is_launch_test(item) for item in session.items):
        return
    from diffctl.testing.isolation import isolated_bus

    bus = isolated_bus()
    bus.__enter__()
    _OPEN[id(session)] = bus


def pytest_sessionfinish(session: Any) -> None:
    bus = _OPEN.pop(id(session), None)
    if bus is not None:
        bus.__exit__(None, None, None)
