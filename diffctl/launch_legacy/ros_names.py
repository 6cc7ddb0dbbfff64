"""The names of ROS 2's `launch`, `launch_ros`, `launch_xml` and `launch_yaml` modules, mapped onto
diffctl.launch_legacy.

The overlay's modules (`diffctl/overlay/launch/…`) are one line each: `export(__name__, globals())` fills the
module with diffctl's objects for ROS's names and gives it a `__getattr__` that names what diffctl lacks in
one line (an AttributeError too, so `hasattr` feature checks see False). Being real modules on `sys.path`,
they import from anywhere: a launch file, an OpaqueFunction called at event time, a node.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from typing import Any

from diffctl.errors import LaunchError

EVENT_MODULES = ("launch.events", "launch.events.process", "launch_ros.events", "launch_ros.events.lifecycle")


class MissingName(LaunchError, AttributeError):
    """A ROS launch name diffctl lacks: one line naming it; still an AttributeError, so `hasattr` feature checks
    in launch files see False instead of failing."""


def missing(module: str, name: str) -> MissingName:
    provided = sorted(k for k in dir(sys.modules.get(module)) if not k.startswith("_")) if module in sys.modules else []
    return MissingName(
        f"{module}.{name} is not supported by diffctl", hint=f"{module} here provides: " + ", ".join(provided)
    )


def _launch_names() -> dict[str, Any]:
    import diffctl.launch_legacy as api
    from diffctl.launch_legacy.context import LaunchContext

    names = {k: getattr(api, k) for k in api.__all__}
    names["LaunchContext"] = LaunchContext
    return names


def _event_names() -> dict[str, Any]:
    from diffctl.launch_legacy import events, lifecycle

    extra = {k: getattr(lifecycle, k) for k in ("ChangeState", "StateTransition", "matches_node_name")}

    return extra | {
        k: v for k, v in vars(events).items() if (not k.startswith("_") and k[0].isupper()) or k.startswith("matches_")
    }


def export(module: str, namespace: dict[str, Any]) -> Callable[[str], Any]:
    """Fill an overlay module's namespace with diffctl's objects; return its module `__getattr__`."""
    names = _event_names() if module in EVENT_MODULES else _launch_names()
    if module == "launch_ros.substitutions":  # there `Parameter` is the substitution, not the node parameter
        from diffctl.launch_legacy.ros_substitutions import ParameterSubstitution

        names = names | {"Parameter": ParameterSubstitution}
    namespace.update(names)
    namespace["__all__"] = sorted(names)

    def __getattr__(name: str) -> Any:
        if name.startswith("__"):
            raise AttributeError(name)
        raise missing(module, name)

    return __getattr__
