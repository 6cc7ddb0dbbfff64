"""The small pairs of ros_gz_bridge's Jazzy table: builtin_interfaces/Time, std_msgs/Header and ColorRGBA,
geometry_msgs/Quaternion, sensor_msgs/Joy, trajectory_msgs/JointTrajectory and rcl_interfaces/ParameterValue,
each as ros_gz_bridge's convert functions (src/convert/*.cpp, jazzy) treat it.

gz layouts: Time `{"sec", "nsec"}`; Header `{"stamp", "data"}`; Color `{"r","g","b","a"}`; Quaternion
`{"x","y","z","w"}`; Joy `{"header", "axes": [f], "buttons": [int]}`; JointTrajectory `{"header",
"joint_names": [str], "points": [{"positions", "velocities", "accelerations", "effort": [f],
"time_from_start": {"sec", "nsec"}}]}`; Any `{"type": "NONE"|"DOUBLE"|"INT32"|"STRING"|"BOOLEAN"|…,
"double_value", "int_value", "string_value", "bool_value"}`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from diffctl.bridge.conversions import (
    GzDict,
    float32_field,
    header_to_gz,
    header_to_ros,
    make_msg,
    quaternion_to_gz,
    quaternion_to_ros,
    time_to_gz,
    time_to_ros,
)
from diffctl.errors import MessageError

INT32_MIN, INT32_MAX = -(2**31), 2**31 - 1
# rcl_interfaces/msg/ParameterType values ros_gz_bridge converts
PARAMETER_NOT_SET, PARAMETER_BOOL, PARAMETER_INTEGER, PARAMETER_DOUBLE, PARAMETER_STRING = 0, 1, 2, 3, 4


def time_msg_to_ros(m: GzDict) -> Any:
    return time_to_ros(m)


def time_msg_to_gz(msg: Any) -> GzDict:
    return time_to_gz(msg)


def header_msg_to_ros(m: GzDict) -> Any:
    return header_to_ros(m)


def header_msg_to_gz(msg: Any) -> GzDict:
    # ros_gz_bridge always writes the frame_id pair, an empty one included
    return {"stamp": time_to_gz(msg.stamp), "data": [{"key": "frame_id", "value": [msg.frame_id]}]}


def color_to_ros(m: GzDict) -> Any:
    return make_msg(
        "std_msgs/msg/ColorRGBA",
        r=float32_field(m, "r"),
        g=float32_field(m, "g"),
        b=float32_field(m, "b"),
        a=float32_field(m, "a"),
    )


def color_to_gz(msg: Any) -> GzDict:
    return {"r": float(msg.r), "g": float(msg.g), "b": float(msg.b), "a": float(msg.a)}


def quaternion_msg_to_ros(m: GzDict) -> Any:
    return quaternion_to_ros(m)


def quaternion_msg_to_gz(msg: Any) -> GzDict:
    return quaternion_to_gz(msg)


def joy_to_ros(m: GzDict) -> Any:
    return make_msg(
        "sensor_msgs/msg/Joy",
        header=header_to_ros(m.get("header")),
        axes=np.asarray(m.get("axes") if m.get("axes") is not None else [], dtype=np.float32),
        buttons=np.asarray(m.get("buttons") if m.get("buttons") is not None else [], dtype=np.int32),
    )


def joy_to_gz(msg: Any) -> GzDict:
    return {
        "header": header_to_gz(msg.header),
        "axes": [float(a) for a in msg.axes],
        "buttons": [int(b) for b in msg.buttons],
    }


def _floats(values: Any) -> np.ndarray:
    return np.asarray(values if values is not None else [], dtype=np.float64)


def _duration_to_ros(d: dict[str, Any] | None) -> Any:
    # rclcpp::Duration(sec, nsec) normalises nanoseconds into [0, 1e9)
    d = d or {}
    total = int(d.get("sec", 0)) * 1_000_000_000 + int(d.get("nsec", 0))
    sec, nanosec = divmod(total, 1_000_000_000)
    return make_msg("builtin_interfaces/msg/Duration", sec=sec, nanosec=nanosec)


def joint_trajectory_to_ros(m: GzDict) -> Any:
    points = [
        make_msg(
            "trajectory_msgs/msg/JointTrajectoryPoint",
            positions=_floats(p.get("positions")),
            velocities=_floats(p.get("velocities")),
            accelerations=_floats(p.get("accelerations")),
            effort=_floats(p.get("effort")),
            time_from_start=_duration_to_ros(p.get("time_from_start")),
        )
        for p in m.get("points") or []
    ]
    return make_msg(
        "trajectory_msgs/msg/JointTrajectory",
        header=header_to_ros(m.get("header")),
        joint_names=[str(n) for n in m.get("joint_names") or []],
        points=points,
    )


def joint_trajectory_to_gz(msg: Any) -> GzDict:
    return {
        "header": header_to_gz(msg.header),
        "joint_names": list(msg.joint_names),
        "points": [
            {
                "positions": [float(v) for v in p.positions],
                "velocities": [float(v) for v in p.velocities],
                "accelerations": [float(v) for v in p.accelerations],
                "effort": [float(v) for v in p.effort],
                "time_from_start": {"sec": int(p.time_from_start.sec), "nsec": int(p.time_from_start.nanosec)},
            }
            for p in msg.points
        ],
    }


def _parameter_value(type_: int, **value: Any) -> Any:
    fields = {
        "type": type_,
        "bool_value": False,
        "integer_value": 0,
        "double_value": 0.0,
        "string_value": "",
        "byte_array_value": np.zeros(0, dtype=np.uint8),
        "bool_array_value": [],
        "integer_array_value": np.zeros(0, dtype=np.int64),
        "double_array_value": np.zeros(0, dtype=np.float64),
        "string_array_value": [],
    }
    fields.update(value)
    return make_msg("rcl_interfaces/msg/ParameterValue", **fields)


def any_to_parameter_value(m: GzDict) -> Any:
    kind = m.get("type", "NONE")
    if kind == "DOUBLE":
        return _parameter_value(PARAMETER_DOUBLE, double_value=float(m.get("double_value", 0.0)))
    if kind == "INT32":
        return _parameter_value(PARAMETER_INTEGER, integer_value=int(m.get("int_value", 0)))
    if kind == "STRING":
        return _parameter_value(PARAMETER_STRING, string_value=str(m.get("string_value", "")))
    if kind == "BOOLEAN":
        return _parameter_value(PARAMETER_BOOL, bool_value=bool(m.get("bool_value", False)))
    if kind in ("NONE", "VECTOR3D", "COLOR", "POSE3D", "QUATERNIOND", "TIME"):
        return _parameter_value(PARAMETER_NOT_SET)  # ros_gz_bridge: "unsupported", left not set
    raise MessageError(f"gz.msgs.Any type {kind!r} is not a gz.msgs.Any.ValueType")


def parameter_value_to_any(msg: Any) -> GzDict:
    t = int(msg.type)
    if t == PARAMETER_BOOL:
        return {"type": "BOOLEAN", "bool_value": bool(msg.bool_value)}
    if t == PARAMETER_INTEGER:
        # ros_gz_bridge clamps to int32
        return {"type": "INT32", "int_value": max(INT32_MIN, min(INT32_MAX, int(msg.integer_value)))}
    if t == PARAMETER_DOUBLE:
        return {"type": "DOUBLE", "double_value": float(msg.double_value)}
    if t == PARAMETER_STRING:
        return {"type": "STRING", "string_value": str(msg.string_value)}
    return {"type": "NONE"}  # not set, and the array types ros_gz_bridge does not convert
