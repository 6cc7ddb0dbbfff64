"""launch_pytest, module for module (ROS 2 Jazzy), on diffctl's launch: pytest-native launch tests.

A `@launch_pytest.fixture` returns a LaunchDescription; tests marked `@pytest.mark.launch(fixture=…)` run
while it is launched (plain, async, generator and async-generator functions; what follows a generator's
`yield` runs after the launch was shut down). The plugin is pytest11 entry point `launch_pytest`; the names
below are imported when first used, so that pytest sessions without launch tests do not import launch.
"""

from __future__ import annotations

from diffctl.launch._private.lazy import lazy_exports

# bound now: importing the module launch_pytest.fixture later must not replace the decorator on this package
from .fixture import fixture as fixture

__getattr__, __dir__, _lazy = lazy_exports(__name__, globals(), {".": ["actions/", "tools/"]})
__all__ = sorted([*_lazy, "fixture"])
