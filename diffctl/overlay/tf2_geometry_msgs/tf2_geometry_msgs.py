"""tf2_geometry_msgs.tf2_geometry_msgs, from diffctl.tf2.geometry."""

from tf2_ros import ConvertRegistration, TransformRegistration

from diffctl.tf2.geometry import (  # noqa: F401
    do_transform_point,
    do_transform_polygon_stamped,
    do_transform_pose,
    do_transform_pose_stamped,
    do_transform_pose_with_covariance_stamped,
    do_transform_vector3,
    from_msg_msg,
    register,
    to_msg_msg,
    transform_covariance,
)

register(TransformRegistration(), ConvertRegistration())
