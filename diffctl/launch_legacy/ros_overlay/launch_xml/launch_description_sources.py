"""`launch_xml.launch_description_sources` on the legacy launch engine (names: launch_legacy/ros_names.py)."""

from diffctl.launch_legacy.ros_names import export as _export

__getattr__ = _export(__name__, globals())
