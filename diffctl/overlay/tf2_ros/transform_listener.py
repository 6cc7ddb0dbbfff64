"""tf2_ros.transform_listener, from diffctl.tf2."""

from diffctl.tf2.ros_io import TransformListener  # noqa: F401
