"""rclpy for users' nodes where no ROS is installed: ROS's names mapped onto diffctl.client.

A sourced ROS 2 installation, earlier on sys.path, wins over this overlay.
"""

from typing import Any

import diffctl.interfaces  # noqa: F401  (the message finder, where no .pth file installed it)
from diffctl.client import runtime as _runtime
from diffctl.client.context import Context, get_default_context
from diffctl.client.parameter import Parameter
from diffctl.client.runtime import (
    InitContextManager,
    init,
    ok,
    shutdown,
    spin,
    spin_once,
    spin_until_future_complete,
    try_shutdown,
)
from diffctl.client.signals import SignalHandlerOptions, install_signal_handlers, uninstall_signal_handlers
from diffctl.client.task import Future
from diffctl.client.utilities import get_rmw_implementation_identifier, remove_ros_args

# As rclpy's own __init__ imports them: `rclpy.utilities`, `rclpy.parameter`, … are attributes after `import rclpy`.
from . import (  # noqa: F401
    constants,
    context,
    destroyable,
    exceptions,
    guard_condition,
    impl,
    parameter,
    signals,
    task,
    utilities,
)
from .impl import implementation_singleton  # noqa: F401  (rclpy's __init__ loads its binding through it)


def create_node(*args: Any, **kwargs: Any) -> Any:
    # rclpy's create_node imports rclpy.node, so rclpy.executors, rclpy.logging, … are attributes afterwards.
    from . import node  # noqa: F401

    return _runtime.create_node(*args, **kwargs)


def get_global_executor() -> Any:
    from . import executors  # noqa: F401  (rclpy's imports rclpy.executors here)

    return _runtime.get_global_executor()


create_node.__doc__ = _runtime.create_node.__doc__
get_global_executor.__doc__ = _runtime.get_global_executor.__doc__

__all__ = [
    "Context",
    "Future",
    "InitContextManager",
    "Parameter",
    "SignalHandlerOptions",
    "create_node",
    "get_default_context",
    "get_global_executor",
    "get_rmw_implementation_identifier",
    "init",
    "install_signal_handlers",
    "ok",
    "remove_ros_args",
    "shutdown",
    "spin",
    "spin_once",
    "spin_until_future_complete",
    "try_shutdown",
    "uninstall_signal_handlers",
]
