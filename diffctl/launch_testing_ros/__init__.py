"""launch_testing_ros, module for module (ROS 2 Jazzy): launch tests of ROS nodes, with rclpy helpers for
test bodies (diffctl's rclpy: diffctl.client). Names are imported when first used: pytest loads this
package's plugin in every session.
"""

from __future__ import annotations

import importlib
from typing import Any

_WHERE = {
    "tools": (".tools", None),
    "DataRepublisher": (".data_republisher", "DataRepublisher"),
    "MessagePump": (".message_pump", "MessagePump"),
    "LaunchTestRunner": (".test_runner", "LaunchTestRunner"),
    "WaitForTopics": (".wait_for_topics", "WaitForTopics"),
}

__all__ = sorted(_WHERE)


def __getattr__(name: str) -> Any:
    if name not in _WHERE:
        return _submodule(name)
    where, attribute = _WHERE[name]
    module = importlib.import_module(where, __name__)
    value = module if attribute is None else getattr(module, attribute)
    globals()[name] = value
    return value


def _submodule(name: str) -> Any:
    """Any submodule is an attribute, as ROS's eager imports make most of them (`launch_testing.util`)."""
    if name.startswith("__"):
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    try:
        return importlib.import_module("." + name, __name__)
    except ModuleNotFoundError as e:
        if e.name != f"{__name__}.{name}":
            raise
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}") from None


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_WHERE))
