"""Pure conversions between simulator-side gz.msgs dicts (layouts in diffctl/bus/gz.py) and ROS messages.

Each supported pair has `<name>_to_ros(gz_dict) -> msg` and `<name>_to_gz(msg) -> gz_dict`; the behaviour
follows ros_gz_bridge's convert functions (frame ids from the gz header's `frame_id` / `child_frame_id`
entries, `::` in gz scoped names becomes `/`, the middle vertical slice of a multi-layer scan). Nothing here
touches the bus: messages are built from the message classes of `diffctl.interfaces.types`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from diffctl.bus import gz
from diffctl.errors import MessageError
from diffctl.interfaces import types

GzDict = dict[str, Any]


def make_msg(typename: str, **fields: Any) -> Any:
    return types.get_class(typename)(**fields)


# --- building blocks -------------------------------------------------------------------------------------


def frame_to_ros(name: str) -> str:
    # Gazebo scopes names with "::" (robot::lidar_link); ROS frame ids use "/".
    return name.replace("::", "/")


def time_to_ros(t: dict[str, Any] | None) -> Any:
    t = t or {}
    return make_msg("builtin_interfaces/msg/Time", sec=int(t.get("sec", 0)), nanosec=int(t.get("nsec", 0)))


def time_to_gz(t: Any) -> dict[str, int]:
    return {"sec": int(t.sec), "nsec": int(t.nanosec)}


def header_to_ros(h: dict[str, Any] | None) -> Any:
    return make_msg(
        "std_msgs/msg/Header",
        stamp=time_to_ros((h or {}).get("stamp")),
        frame_id=frame_to_ros(gz.header_value(h, "frame_id")),
    )


def header_to_gz(h: Any, child_frame_id: str | None = None) -> GzDict:
    data = [{"key": "frame_id", "value": [h.frame_id]}] if h.frame_id else []
    if child_frame_id:
        data.append({"key": "child_frame_id", "value": [child_frame_id]})
    return {"stamp": time_to_gz(h.stamp), "data": data}


def float_field(d: dict[str, Any] | None, name: str, default: float = 0.0) -> float:
    return float((d or {}).get(name, default))


def float32_field(d: dict[str, Any] | None, name: str) -> float:
    # float32 fields carry what the wire will carry, so a round trip compares equal.
    return float(np.float32(float_field(d, name)))


def vector3_to_ros(v: dict[str, Any] | None, typename: str = "geometry_msgs/msg/Vector3") -> Any:
    return make_msg(typename, x=float_field(v, "x"), y=float_field(v, "y"), z=float_field(v, "z"))


def vector3_to_gz(v: Any) -> dict[str, float]:
    return {"x": float(v.x), "y": float(v.y), "z": float(v.z)}


def quaternion_to_ros(q: dict[str, Any] | None) -> Any:
    # protobuf's default for an absent quaternion is all zeros; gz treats a missing orientation as identity.
    w = float_field(q, "w", 1.0 if not q else 0.0)
    return make_msg(
        "geometry_msgs/msg/Quaternion", x=float_field(q, "x"), y=float_field(q, "y"), z=float_field(q, "z"), w=w
    )


def quaternion_to_gz(q: Any) -> dict[str, float]:
    return {"x": float(q.x), "y": float(q.y), "z": float(q.z), "w": float(q.w)}


def pose_to_ros(p: dict[str, Any] | None) -> Any:
    p = p or {}
    return make_msg(
        "geometry_msgs/msg/Pose",
        position=vector3_to_ros(p.get("position"), "geometry_msgs/msg/Point"),
        orientation=quaternion_to_ros(p.get("orientation")),
    )


def pose_fields_to_gz(p: Any) -> GzDict:
    return {"position": vector3_to_gz(p.position), "orientation": quaternion_to_gz(p.orientation)}


def twist_to_ros(t: dict[str, Any] | None) -> Any:
    t = t or {}
    return make_msg(
        "geometry_msgs/msg/Twist", linear=vector3_to_ros(t.get("linear")), angular=vector3_to_ros(t.get("angular"))
    )


def require_finite(values: list[float], what: str) -> None:
    # A NaN or inf velocity or pose must never reach the physics: drop the message instead.
    if not all(math.isfinite(v) for v in values):
        raise MessageError(f"{what} with a non-finite value {values} dropped")


def _twist_fields_to_gz(t: Any, what: str) -> GzDict:
    lin, ang = vector3_to_gz(t.linear), vector3_to_gz(t.angular)
    require_finite([*lin.values(), *ang.values()], what)
    return {"linear": lin, "angular": ang}


def zero_covariance(n: int) -> np.ndarray:
    return np.zeros(n, dtype=np.float64)


# --- rosgraph_msgs/msg/Clock <-> gz.msgs.Clock -----------------------------------------------------------


def clock_to_ros(m: GzDict) -> Any:
    return make_msg("rosgraph_msgs/msg/Clock", clock=time_to_ros(m.get("sim")))


def clock_to_gz(msg: Any) -> GzDict:
    t = time_to_gz(msg.clock)
    return {"header": {"stamp": dict(t), "data": []}, "sim": t}


# --- geometry_msgs/msg/Twist(Stamped) <-> gz.msgs.Twist ---------------------------------------------------


def twist_to_gz(msg: Any) -> GzDict:
    return _twist_fields_to_gz(msg, "geometry_msgs/msg/Twist")


def twist_stamped_to_ros(m: GzDict) -> Any:
    return make_msg("geometry_msgs/msg/TwistStamped", header=header_to_ros(m.get("header")), twist=twist_to_ros(m))


def twist_stamped_to_gz(msg: Any) -> GzDict:
    return {"header": header_to_gz(msg.header), **_twist_fields_to_gz(msg.twist, "geometry_msgs/msg/TwistStamped")}


# --- nav_msgs/msg/Odometry <-> gz.msgs.Odometry -----------------------------------------------------------


def odometry_to_ros(m: GzDict) -> Any:
    h = m.get("header")
    return make_msg(
        "nav_msgs/msg/Odometry",
        header=header_to_ros(h),
        child_frame_id=frame_to_ros(gz.header_value(h, "child_frame_id")),
        pose=make_msg(
            "geometry_msgs/msg/PoseWithCovariance", pose=pose_to_ros(m.get("pose")), covariance=zero_covariance(36)
        ),
        twist=make_msg(
            "geometry_msgs/msg/TwistWithCovariance",
            twist=twist_to_ros(m.get("twist")),
            covariance=zero_covariance(36),
        ),
    )


def odometry_to_gz(msg: Any) -> GzDict:
    return {
        "header": header_to_gz(msg.header, msg.child_frame_id),
        "pose": pose_fields_to_gz(msg.pose.pose),
        "twist": {"linear": vector3_to_gz(msg.twist.twist.linear), "angular": vector3_to_gz(msg.twist.twist.angular)},
    }


# --- sensor_msgs/msg/JointState <-> gz.msgs.Model (JointStatePublisher output) -------------------------------


def model_to_joint_state(m: GzDict) -> Any:
    joints = m.get("joint") or []
    names, pos, vel, eff = [], [], [], []
    for j in joints:
        axis = j.get("axis1") or {}
        names.append(frame_to_ros(str(j.get("name", ""))))
        pos.append(float_field(axis, "position"))
        vel.append(float_field(axis, "velocity"))
        eff.append(float_field(axis, "force"))
    return make_msg(
        "sensor_msgs/msg/JointState",
        header=header_to_ros(m.get("header")),
        name=names,
        position=np.array(pos, dtype=np.float64),
        velocity=np.array(vel, dtype=np.float64),
        effort=np.array(eff, dtype=np.float64),
    )


def joint_state_to_model(msg: Any) -> GzDict:
    n = len(msg.name)

    def at(arr: Any, i: int) -> float:
        # JointState allows empty position/velocity/effort arrays ("not known").
        return float(arr[i]) if i < len(arr) else 0.0

    joints = [
        {
            "name": msg.name[i],
            "axis1": {"position": at(msg.position, i), "velocity": at(msg.velocity, i), "force": at(msg.effort, i)},
        }
        for i in range(n)
    ]
    return {"header": header_to_gz(msg.header), "name": "", "joint": joints}


# --- tf2_msgs/msg/TFMessage <-> gz.msgs.Pose_V ------------------------------------------------------------


def pose_v_to_tf(m: GzDict) -> Any:
    outer_stamp = (m.get("header") or {}).get("stamp")
    transforms = []
    for p in m.get("pose") or []:
        h = p.get("header") or {}
        stamp = h.get("stamp") or outer_stamp
        # PosePublisher names the child in the header; a bare pose falls back to its entity name.
        child = gz.header_value(h, "child_frame_id") or str(p.get("name", ""))
        transforms.append(
            make_msg(
                "geometry_msgs/msg/TransformStamped",
                header=make_msg(
                    "std_msgs/msg/Header",
                    stamp=time_to_ros(stamp),
                    frame_id=frame_to_ros(gz.header_value(h, "frame_id")),
                ),
                child_frame_id=frame_to_ros(child),
                transform=make_msg(
                    "geometry_msgs/msg/Transform",
                    translation=vector3_to_ros(p.get("position")),
                    rotation=quaternion_to_ros(p.get("orientation")),
                ),
            )
        )
    return make_msg("tf2_msgs/msg/TFMessage", transforms=transforms)


def tf_to_pose_v(msg: Any) -> GzDict:
    poses = []
    for t in msg.transforms:
        poses.append(
            {
                "name": t.child_frame_id,
                "header": header_to_gz(t.header, t.child_frame_id),
                "position": vector3_to_gz(t.transform.translation),
                "orientation": quaternion_to_gz(t.transform.rotation),
            }
        )
    stamp = poses[0]["header"]["stamp"] if poses else {"sec": 0, "nsec": 0}
    return {"header": {"stamp": dict(stamp), "data": []}, "pose": poses}


# --- geometry_msgs/msg/Pose(Stamped) <-> gz.msgs.Pose -----------------------------------------------------


def pose_to_gz(msg: Any) -> GzDict:
    out = pose_fields_to_gz(msg)
    require_finite([*out["position"].values(), *out["orientation"].values()], "geometry_msgs/msg/Pose")
    return out


def pose_stamped_to_ros(m: GzDict) -> Any:
    return make_msg("geometry_msgs/msg/PoseStamped", header=header_to_ros(m.get("header")), pose=pose_to_ros(m))


def pose_stamped_to_gz(msg: Any) -> GzDict:
    return {"header": header_to_gz(msg.header), "name": "", **pose_to_gz(msg.pose)}


# --- std_msgs scalars <-> gz.msgs scalars -----------------------------------------------------------------


def scalar_to_ros(ros_type: str, cast: type) -> Any:
    def convert(m: GzDict) -> Any:
        return make_msg(ros_type, data=cast(m.get("data", cast())))

    return convert


def scalar_to_gz(cast: type, finite: bool = False) -> Any:
    def convert(msg: Any) -> GzDict:
        value = cast(msg.data)
        if finite:
            require_finite([value], "scalar command")
        return {"data": value}

    return convert


# --- std_msgs/msg/Empty <-> gz.msgs.Empty -----------------------------------------------------------------


def empty_to_ros(m: GzDict) -> Any:
    return make_msg("std_msgs/msg/Empty", structure_needs_at_least_one_member=0)


def empty_to_gz(msg: Any) -> GzDict:
    return {}
