"""rosidl_runtime_py's functions (Jazzy) over any rosidl-style message classes: conversions to dicts, YAML
and CSV, setting fields from dicts, and finding interfaces by name. The overlay's `rosidl_runtime_py`
package maps ROS's module names onto these."""
