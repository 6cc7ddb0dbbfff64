"""The message bus: Zenoh sessions, ROS-like nodes and the rmw_zenoh wire format. See API.md.

Names are imported on first use, so `diffctl.bus.router` (the launcher's embedded router) does not pull in
numpy and the typestore.
"""

from __future__ import annotations

import importlib
from typing import Any

_LAZY = {
    "Node": "diffctl.bus.node",
    "close_session": "diffctl.bus.session",
    "domain_id": "diffctl.bus.session",
    "open_session": "diffctl.bus.session",
    "router_endpoint": "diffctl.bus.session",
}
_MODULES = {"gz", "wire", "graph", "session", "router", "probes"}

__all__ = ["Node", "close_session", "domain_id", "gz", "open_session", "router_endpoint", "types"]


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        return getattr(importlib.import_module(_LAZY[name]), name)
    if name in _MODULES:
        return importlib.import_module(f"diffctl.bus.{name}")
    if name == "types":  # transitional: the types moved to diffctl.interfaces (goes with the bus node)
        return importlib.import_module("diffctl.interfaces.types")
    raise AttributeError(f"module 'diffctl.bus' has no attribute {name!r}")
