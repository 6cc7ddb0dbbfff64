"""launch_pytest, module for module (ROS 2 Jazzy), on diffctl's launch: pytest-native launch tests.

A `@launch_pytest.fixture` returns a LaunchDescription; tests marked `@pytest.mark.launch(fixture=…)` run
while it is launched (plain, async, generator and async-generator functions; what follows a generator's
`yield` runs after the launch was shut down). The plugin is pytest11 entry point `launch_pytest`; the names
below are imported when first used, so that pytest sessions without launch tests do not import launch.
"""

from __future__ import annotations

import importlib
from typing import Any

# bound now: importing the module launch_pytest.fixture later must not replace the decorator on this package
from .fixture import fixture

_WHERE = {"actions": ".actions", "tools": ".tools"}

__all__ = ["actions", "fixture", "tools"]


def __getattr__(name: str) -> Any:
    where = _WHERE.get(name)
    if where is None:
        return _submodule(name)
    module = importlib.import_module(where, __name__)
    globals()[name] = module
    return module


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
