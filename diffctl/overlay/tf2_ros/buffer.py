"""tf2_ros.buffer, from diffctl.tf2."""

from diffctl.tf2.ros_io import Buffer  # noqa: F401
