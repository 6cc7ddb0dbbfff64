"""tf2_ros.static_transform_broadcaster, from diffctl.tf2."""

from diffctl.tf2.ros_io import StaticTransformBroadcaster  # noqa: F401
