"""`launch_testing` on diffctl's launch engine (the work: diffctl/testing/)."""

from diffctl.testing.decorators import parametrize, post_shutdown_test, ready_to_test_action_timeout
from diffctl.testing.handlers import ActiveIoHandler, ActiveProcInfoHandler, IoHandler, ProcInfoHandler
from diffctl.testing.ready_aggregator import ReadyAggregator

from . import actions, asserts, markers, tools, util  # noqa: F401 (reachable as attributes, as ROS's)

__all__ = [
    "ActiveIoHandler",
    "ActiveProcInfoHandler",
    "IoHandler",
    "ProcInfoHandler",
    "ReadyAggregator",
    "parametrize",
    "post_shutdown_test",
    "ready_to_test_action_timeout",
]
