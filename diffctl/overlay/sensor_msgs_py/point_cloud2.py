"""sensor_msgs_py.point_cloud2, from diffctl.interfaces.point_cloud2."""

from diffctl.interfaces.point_cloud2 import (  # noqa: F401
    DUMMY_FIELD_PREFIX,
    create_cloud,
    create_cloud_xyz32,
    dtype_from_fields,
    read_points,
    read_points_list,
    read_points_numpy,
)
