"""Matchers of Node actions by their fully qualified node name."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any


def matches_node_name(node_name: str) -> Callable[[Any], bool]:
    """A matcher of the node named `node_name` (`talker` is read as `/talker`)."""
    fqn = node_name if node_name.startswith("/") else f"/{node_name}"
    return lambda action: action.node_name == fqn
