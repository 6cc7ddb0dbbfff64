"""The old home of `matches_node_name` (now launch_ros.events.matchers): still there, with a warning."""

from __future__ import annotations

import warnings
from collections.abc import Callable
from typing import Any

from ..matchers import matches_node_name as _matches_node_name


def matches_node_name(node_name: str) -> Callable[[Any], bool]:
    """A matcher of the node named `node_name`; use launch_ros.events.matchers.matches_node_name."""
    warnings.warn(
        "'matches_node_name' has been moved into the 'launch.events' module and will be removed "
        "from the 'lifecycle' module in the future",
        stacklevel=2,
    )
    return _matches_node_name(node_name)
