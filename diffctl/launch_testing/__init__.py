"""launch_testing, module for module (ROS 2 Jazzy), on diffctl's launch: integration tests that launch
processes, test them while they run and after they have ended.

`diffctl test` (diffctl/testing/) runs files of these on a Zenoh router and ROS domain of their own. The
names below are imported when first used: pytest loads this package's plugin in every session, and the
launch library costs a second to import.
"""

from __future__ import annotations

import importlib
from typing import Any

# light modules whose names are also their functions' names: bound now, so that importing the module later
# cannot replace the function on this package
from .decorator import post_shutdown_test
from .parametrize import parametrize
from .ready_aggregator import ReadyAggregator
from .ready_to_test_action_timeout import ready_to_test_action_timeout

_WHERE = {
    "tools": ".tools",
    "ActiveIoHandler": ".io_handler",
    "IoHandler": ".io_handler",
    "ActiveProcInfoHandler": ".proc_info_handler",
    "ProcInfoHandler": ".proc_info_handler",
}

__all__ = [
    "ActiveIoHandler",
    "ActiveProcInfoHandler",
    "IoHandler",
    "ProcInfoHandler",
    "ReadyAggregator",
    "parametrize",
    "post_shutdown_test",
    "ready_to_test_action_timeout",
    "tools",
]


def __getattr__(name: str) -> Any:
    where = _WHERE.get(name)
    if where is None:
        return _submodule(name)
    module = importlib.import_module(where, __name__)
    value = module if where == "." + name else getattr(module, name)
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
