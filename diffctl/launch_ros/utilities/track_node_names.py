"""How many nodes of each fully qualified name a launch has started (launch_ros warns about duplicates)."""

from __future__ import annotations

from collections import Counter

from diffctl.launch.launch_context import LaunchContext

_KEY = "unique_ros_node_names"


def add_node_name(context: LaunchContext, node_name: str) -> None:
    """Count one more node named `node_name` in this launch."""
    counts = getattr(context.locals, _KEY, None)
    if counts is None:
        counts = Counter()
        context.extend_globals({_KEY: counts})
    counts[node_name] += 1


def get_node_name_count(context: LaunchContext, node_name: str) -> int:
    """How many nodes named `node_name` this launch has counted (0 when none)."""
    counts = getattr(context.locals, _KEY, None)
    return 0 if counts is None else counts[node_name]
