"""How every demo node runs: init with the process's ROS arguments, spin until Ctrl-C or shutdown, clean up."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import rclpy
from rclpy.executors import ExternalShutdownException


def spin_node(make: Callable[[], Any]) -> int:
    rclpy.init()
    node = None
    try:
        node = make()
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        if node is not None:
            node.destroy_node()
        rclpy.try_shutdown()
    return 0
