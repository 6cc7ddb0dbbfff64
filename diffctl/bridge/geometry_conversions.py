"""Pure conversions of the further geometry_msgs pairs ros_gz_bridge offers (src/convert/geometry_msgs.cpp):
Vector3 / Point ↔ gz.msgs.Vector3d, PoseArray ↔ gz.msgs.Pose_V, Transform(Stamped) ↔ gz.msgs.Pose (the
child frame in the gz header's `child_frame_id` entry) and Wrench(Stamped) ↔ gz.msgs.Wrench.

Everything that goes to the simulator is checked finite first: a NaN pose or force never reaches physics.
"""

from __future__ import annotations

from typing import Any

from diffctl.bridge.conversions import (
    GzDict,
    frame_to_ros,
    header_to_gz,
    header_to_ros,
    make_msg,
    pose_to_gz,
    pose_to_ros,
    quaternion_to_gz,
    quaternion_to_ros,
    require_finite,
    vector3_to_gz,
    vector3_to_ros,
)
from diffctl.bus import gz


def _finite_vector(v: Any, what: str) -> dict[str, float]:
    out = vector3_to_gz(v)
    require_finite(list(out.values()), what)
    return out


# --- geometry_msgs/msg/Vector3, Point <-> gz.msgs.Vector3d --------------------------------------------------


def vector3d_to_ros(ros_type: str) -> Any:
    def convert(m: GzDict) -> Any:
        return vector3_to_ros(m, ros_type)

    return convert


def vector3d_to_gz(msg: Any) -> GzDict:
    return _finite_vector(msg, "vector")


# --- geometry_msgs/msg/PoseArray <-> gz.msgs.Pose_V ---------------------------------------------------------


def pose_v_to_pose_array(m: GzDict) -> Any:
    return make_msg(
        "geometry_msgs/msg/PoseArray",
        header=header_to_ros(m.get("header")),
        poses=[pose_to_ros(p) for p in m.get("pose") or []],
    )


def pose_array_to_pose_v(msg: Any) -> GzDict:
    return {"header": header_to_gz(msg.header), "pose": [pose_to_gz(p) for p in msg.poses]}


# --- geometry_msgs/msg/Transform(Stamped) <-> gz.msgs.Pose --------------------------------------------------


def pose_to_transform(m: GzDict) -> Any:
    return make_msg(
        "geometry_msgs/msg/Transform",
        translation=vector3_to_ros(m.get("position")),
        rotation=quaternion_to_ros(m.get("orientation")),
    )


def transform_to_pose(t: Any) -> GzDict:
    orientation = quaternion_to_gz(t.rotation)
    require_finite(list(orientation.values()), "geometry_msgs/msg/Transform rotation")
    return {"position": _finite_vector(t.translation, "geometry_msgs/msg/Transform"), "orientation": orientation}


def pose_to_transform_stamped(m: GzDict) -> Any:
    h = m.get("header")
    return make_msg(
        "geometry_msgs/msg/TransformStamped",
        header=header_to_ros(h),
        child_frame_id=frame_to_ros(gz.header_value(h, "child_frame_id")),
        transform=pose_to_transform(m),
    )


def transform_stamped_to_pose(msg: Any) -> GzDict:
    return {
        "header": header_to_gz(msg.header, msg.child_frame_id),
        "name": "",
        **transform_to_pose(msg.transform),
    }


# --- geometry_msgs/msg/Wrench(Stamped) <-> gz.msgs.Wrench ---------------------------------------------------


def wrench_to_ros(m: GzDict) -> Any:
    return make_msg(
        "geometry_msgs/msg/Wrench", force=vector3_to_ros(m.get("force")), torque=vector3_to_ros(m.get("torque"))
    )


def wrench_to_gz(w: Any) -> GzDict:
    return {"force": _finite_vector(w.force, "wrench force"), "torque": _finite_vector(w.torque, "wrench torque")}


def wrench_stamped_to_ros(m: GzDict) -> Any:
    return make_msg("geometry_msgs/msg/WrenchStamped", header=header_to_ros(m.get("header")), wrench=wrench_to_ros(m))


def wrench_stamped_to_gz(msg: Any) -> GzDict:
    return {"header": header_to_gz(msg.header), **wrench_to_gz(msg.wrench)}
