"""`launch_ros` on diffctl's launch engine (the names: diffctl/launch_legacy/ros_names.py)."""

import importlib

from diffctl.launch_legacy.ros_names import export as _export

__getattr__ = _export(__name__, globals())

# As ROS's package, importing it makes its submodules reachable as attributes.
for _name in ("actions", "descriptions", "event_handlers", "parameter_descriptions", "substitutions"):
    importlib.import_module(f"{__name__}.{_name}")
