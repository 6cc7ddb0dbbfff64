"""`launch_ros.events.lifecycle` on diffctl's launch engine (the names: diffctl/launch_legacy/ros_names.py)."""

from diffctl.launch_legacy.ros_names import export as _export

__getattr__ = _export(__name__, globals())
