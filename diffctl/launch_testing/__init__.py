"""launch_testing, module for module (ROS 2 Jazzy), on diffctl's launch: integration tests that launch
processes, test them while they run and after they have ended.

`diffctl test` (diffctl/testing/) runs files of these on a Zenoh router and ROS domain of their own. The
names below are imported when first used: pytest loads this package's plugin in every session, and the
launch library costs a second to import.
"""

from __future__ import annotations

from diffctl.launch._private.lazy import lazy_exports

# light modules whose names are also their functions' names: bound now, so that importing the module later
# cannot replace the function on this package
from .decorator import post_shutdown_test as post_shutdown_test
from .parametrize import parametrize as parametrize
from .ready_aggregator import ReadyAggregator as ReadyAggregator
from .ready_to_test_action_timeout import ready_to_test_action_timeout as ready_to_test_action_timeout

__getattr__, __dir__, _lazy = lazy_exports(__name__, globals(), {
    ".": ["tools/"],
    ".io_handler": ["ActiveIoHandler", "IoHandler"],
    ".proc_info_handler": ["ActiveProcInfoHandler", "ProcInfoHandler"],
})
__all__ = sorted([*_lazy, "ReadyAggregator", "parametrize", "post_shutdown_test", "ready_to_test_action_timeout"])
