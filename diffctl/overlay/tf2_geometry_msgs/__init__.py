"""tf2_geometry_msgs: do_transform_* for geometry_msgs, registered with tf2_ros's Buffer.transform()."""

from tf2_geometry_msgs.tf2_geometry_msgs import (  # noqa: F401
    do_transform_point,
    do_transform_polygon_stamped,
    do_transform_pose,
    do_transform_pose_stamped,
    do_transform_pose_with_covariance_stamped,
    do_transform_vector3,
    from_msg_msg,
    to_msg_msg,
    transform_covariance,
)
