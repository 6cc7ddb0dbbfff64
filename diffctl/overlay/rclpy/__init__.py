"""rclpy for users' nodes where no ROS is installed: ROS's names mapped onto diffctl.client.

A sourced ROS 2 installation, earlier on sys.path, wins over this overlay.
"""

import diffctl.client.messages  # noqa: F401  (the message finder, where no .pth file installed it)
from diffctl.client.context import Context, get_default_context
from diffctl.client.runtime import (
    InitContextManager,
    create_node,
    get_global_executor,
    init,
    ok,
    shutdown,
    spin,
    spin_once,
    spin_until_future_complete,
    try_shutdown,
)
from diffctl.client.utilities import get_rmw_implementation_identifier, remove_ros_args

__all__ = [
    "Context",
    "InitContextManager",
    "create_node",
    "get_default_context",
    "get_global_executor",
    "get_rmw_implementation_identifier",
    "init",
    "ok",
    "remove_ros_args",
    "shutdown",
    "spin",
    "spin_once",
    "spin_until_future_complete",
    "try_shutdown",
]
