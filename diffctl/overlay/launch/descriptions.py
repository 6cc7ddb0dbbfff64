"""`launch.descriptions` on diffctl's launch engine (the names: diffctl/launch/ros_names.py)."""

from diffctl.launch.ros_names import export as _export

__getattr__ = _export(__name__, globals())
