"""The simulator side of the bus: Gazebo-transport-like topics under the Zenoh key prefix `gz/`.

The simulator is not a ROS node, so its topics are invisible to ROS tools: they live under `gz/` and carry
gz.msgs messages encoded as JSON in protobuf's JSON naming (the shape `gz topic -e --json-output`
prints), one object per sample with its type in `"@type"`. Bytes fields (image data) are base64;
non-finite floats are written as JSON's NaN / Infinity literals. The bridge converts these to ROS types.

Message layouts used by diffctl (field names as in gz-msgs .proto files):
  gz.msgs.Clock      {"header": H, "sim": T, "real": T, "system": T}
  gz.msgs.Twist      {"header": H, "linear": V3, "angular": V3}
  gz.msgs.Odometry   {"header": H, "pose": {"position": V3, "orientation": Q}, "twist": {"linear": V3, "angular": V3}}
  gz.msgs.Model      {"header": H, "name": str, "joint": [{"name": str, "axis1": {"position": f, "velocity": f,
                      "force": f}}]}   (JointStatePublisher output)
  gz.msgs.Pose_V     {"header": H, "pose": [{"name": str, "header": H, "position": V3, "orientation": Q}]}
                      (each pose's header carries frame_id / child_frame_id in its "data" list)
  gz.msgs.LaserScan  {"header": H, "frame": str, "world_pose": P, "angle_min": f, "angle_max": f,
                      "angle_step": f, "range_min": f, "range_max": f, "count": n, "vertical_angle_min": f,
                      "vertical_angle_max": f, "vertical_angle_step": f, "vertical_count": n,
                      "ranges": [f], "intensities": [f]}
  gz.msgs.IMU        {"header": H, "entity_name": str, "orientation": Q, "angular_velocity": V3,
                      "linear_acceleration": V3}
  gz.msgs.Image      {"header": H, "width": n, "height": n, "step": n, "pixel_format_type": "RGB_INT8",
                      "data": base64 str}
  where H = {"stamp": T, "data": [{"key": "frame_id", "value": [str]}, {"key": "child_frame_id", ...}]},
        T = {"sec": int, "nsec": int}, V3 = {"x","y","z"}, Q = {"x","y","z","w"}, P = {"position", "orientation"}.
Missing fields take protobuf defaults (0, "", empty list).
"""

from __future__ import annotations

import json
from typing import Any

from diffctl.errors import MessageError

PREFIX = "gz"


def key(topic: str) -> str:
    """Zenoh key of a gz topic name: `/model/robot/cmd_vel` → `gz/model/robot/cmd_vel`."""
    t = topic.strip("/")
    if not t:
        raise MessageError(f"empty gz topic name {topic!r}")
    return f"{PREFIX}/{t}"


def topic_of(key_expr: str) -> str:
    """Inverse of `key`: `gz/lidar` → `/lidar`."""
    k = str(key_expr)
    return "/" + k[len(PREFIX) + 1 :] if k.startswith(PREFIX + "/") else "/" + k


def encode(gz_type: str, msg: dict[str, Any]) -> bytes:
    return json.dumps({"@type": gz_type, **msg}, separators=(",", ":")).encode()


def decode(payload: bytes | bytearray | memoryview, expected_type: str | None = None) -> tuple[str, dict[str, Any]]:
    """(type, fields) of a gz sample; raises MessageError on malformed data or an unexpected type."""
    try:
        obj = json.loads(bytes(payload))
    except (ValueError, UnicodeDecodeError) as e:
        raise MessageError(f"malformed gz message: {e}") from None
    if not isinstance(obj, dict) or not isinstance(obj.get("@type"), str):
        raise MessageError("malformed gz message: not an object with an '@type'")
    gz_type = obj.pop("@type")
    if expected_type is not None and gz_type != expected_type:
        raise MessageError(f"gz message of type {gz_type}, expected {expected_type}")
    return gz_type, obj


def stamp(sim_time_ns: int) -> dict[str, int]:
    return {"sec": sim_time_ns // 1_000_000_000, "nsec": sim_time_ns % 1_000_000_000}


def header(sim_time_ns: int, frame_id: str | None = None, child_frame_id: str | None = None) -> dict[str, Any]:
    data = []
    if frame_id is not None:
        data.append({"key": "frame_id", "value": [frame_id]})
    if child_frame_id is not None:
        data.append({"key": "child_frame_id", "value": [child_frame_id]})
    return {"stamp": stamp(sim_time_ns), "data": data}


def header_value(h: dict[str, Any] | None, name: str, default: str = "") -> str:
    for item in (h or {}).get("data", []):
        if item.get("key") == name and item.get("value"):
            return str(item["value"][0])
    return default


def stamp_ns(h: dict[str, Any] | None) -> int:
    s = (h or {}).get("stamp") or {}
    return int(s.get("sec", 0)) * 1_000_000_000 + int(s.get("nsec", 0))
