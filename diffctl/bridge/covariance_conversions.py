"""Pose, twist and odometry with covariance, as ros_gz_bridge converts them (ros_gz_bridge/src/convert/
geometry_msgs.cpp, nav_msgs.cpp, jazzy).

gz.msgs.PoseWithCovariance is `{"pose": gz.msgs.Pose, "covariance": {"data": [36 f]}}` and
gz.msgs.TwistWithCovariance `{"twist": gz.msgs.Twist, "covariance": {"data": [36 f]}}`; the stamped ROS types
take their header from the inner pose's / twist's header. A covariance of any other length than 36 is left
at zeros, as ros_gz_bridge does. gz.msgs.OdometryWithCovariance is `{"header": H, "pose_with_covariance": …,
"twist_with_covariance": …}` with the child frame in the header.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from diffctl.bridge.conversions import (
    GzDict,
    frame_to_ros,
    header_to_gz,
    header_to_ros,
    make_msg,
    pose_fields_to_gz,
    pose_to_ros,
    twist_to_ros,
    vector3_to_gz,
)
from diffctl.bus import gz


def _covariance_to_ros(c: dict[str, Any] | None) -> np.ndarray:
    data = np.asarray((c or {}).get("data") or [], dtype=np.float64)
    return data.copy() if data.size == 36 else np.zeros(36, dtype=np.float64)


def _covariance_to_gz(values: Any) -> dict[str, Any]:
    return {"data": [float(v) for v in values]}


def pose_with_covariance_to_ros(m: GzDict) -> Any:
    return make_msg(
        "geometry_msgs/msg/PoseWithCovariance",
        pose=pose_to_ros(m.get("pose")),
        covariance=_covariance_to_ros(m.get("covariance")),
    )


def pose_with_covariance_to_gz(msg: Any) -> GzDict:
    return {"pose": pose_fields_to_gz(msg.pose), "covariance": _covariance_to_gz(msg.covariance)}


def pose_with_covariance_stamped_to_ros(m: GzDict) -> Any:
    return make_msg(
        "geometry_msgs/msg/PoseWithCovarianceStamped",
        header=header_to_ros((m.get("pose") or {}).get("header")),
        pose=pose_with_covariance_to_ros(m),
    )


def pose_with_covariance_stamped_to_gz(msg: Any) -> GzDict:
    out = pose_with_covariance_to_gz(msg.pose)
    out["pose"]["header"] = header_to_gz(msg.header)
    return out


def twist_with_covariance_to_ros(m: GzDict) -> Any:
    return make_msg(
        "geometry_msgs/msg/TwistWithCovariance",
        twist=twist_to_ros(m.get("twist")),
        covariance=_covariance_to_ros(m.get("covariance")),
    )


def twist_with_covariance_to_gz(msg: Any) -> GzDict:
    t = msg.twist
    return {
        "twist": {"linear": vector3_to_gz(t.linear), "angular": vector3_to_gz(t.angular)},
        "covariance": _covariance_to_gz(msg.covariance),
    }


def twist_with_covariance_stamped_to_ros(m: GzDict) -> Any:
    return make_msg(
        "geometry_msgs/msg/TwistWithCovarianceStamped",
        header=header_to_ros((m.get("twist") or {}).get("header")),
        twist=twist_with_covariance_to_ros(m),
    )


def twist_with_covariance_stamped_to_gz(msg: Any) -> GzDict:
    out = twist_with_covariance_to_gz(msg.twist)
    out["twist"]["header"] = header_to_gz(msg.header)
    return out


def odometry_with_covariance_to_ros(m: GzDict) -> Any:
    h = m.get("header")
    return make_msg(
        "nav_msgs/msg/Odometry",
        header=header_to_ros(h),
        child_frame_id=frame_to_ros(gz.header_value(h, "child_frame_id")),
        pose=pose_with_covariance_to_ros(m.get("pose_with_covariance") or {}),
        twist=twist_with_covariance_to_ros(m.get("twist_with_covariance") or {}),
    )


def odometry_with_covariance_to_gz(msg: Any) -> GzDict:
    return {
        "header": header_to_gz(msg.header, msg.child_frame_id),
        "pose_with_covariance": pose_with_covariance_to_gz(msg.pose),
        "twist_with_covariance": twist_with_covariance_to_gz(msg.twist),
    }
