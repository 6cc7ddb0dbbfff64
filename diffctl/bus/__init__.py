"""The wire: Zenoh sessions, rmw_zenoh's keys, tokens and attachments, endpoints, the graph. See API.md.

Names are imported on first use, so `diffctl.bus.router` (the launcher's embedded router) does not pull in
numpy and the typestore.
"""

from __future__ import annotations

import importlib
from typing import Any

_LAZY = {
    "Participant": "diffctl.bus.participant",
    "close_session": "diffctl.bus.session",
    "domain_id": "diffctl.bus.session",
    "open_session": "diffctl.bus.session",
    "router_endpoint": "diffctl.bus.session",
}
_MODULES = {"gz", "wire", "graph", "session", "router", "probes"}

__all__ = ["Participant", "close_session", "domain_id", "gz", "open_session", "router_endpoint"]


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        return getattr(importlib.import_module(_LAZY[name]), name)
    if name in _MODULES:
        return importlib.import_module(f"diffctl.bus.{name}")
    raise AttributeError(f"module 'diffctl.bus' has no attribute {name!r}")
