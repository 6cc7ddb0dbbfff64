"""tf2_ros.transform_broadcaster, from diffctl.tf2."""

from diffctl.tf2.ros_io import TransformBroadcaster  # noqa: F401
