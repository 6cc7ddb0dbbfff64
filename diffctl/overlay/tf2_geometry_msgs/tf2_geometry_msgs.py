"""tf2_geometry_msgs.tf2_geometry_msgs, from diffctl.tf2.geometry."""

from diffctl.tf2.geometry import (  # noqa: F401
    do_transform_point,
    do_transform_pose,
    do_transform_pose_stamped,
    do_transform_vector3,
    register,
)
from diffctl.tf2.ros_io import TransformRegistration

register(TransformRegistration())
