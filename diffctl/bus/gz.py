"""The simulator side of the bus: Gazebo-transport-like topics under the Zenoh key prefix `gz/`.

The simulator is not a ROS node, so its topics are invisible to ROS tools: they live under `gz/` and carry
gz.msgs messages as dicts in a compact binary encoding, MessagePack: one sample is the two-element array
`[gz_type, fields]`. Why MessagePack rather than JSON or gz-msgs protobuf: it is bytes-native (image and
point-cloud data travel as raw `bin`, no base64), C-accelerated in both directions, schema-free (the sim's
producers keep passing plain dicts, no generated classes to keep in step with gz-msgs), and a clock sample
is 116 bytes instead of JSON's 190.

Conventions every producer and consumer follows (the contract with the sim's sensors and systems):
- field names are those of the gz-msgs .proto files; missing fields take protobuf defaults (0, "", []);
- bytes fields (Image.data, PointCloudPacked.data) are raw `bytes`;
- enums are their NAME strings ("RGB_INT8", "R_FLOAT32", PointCloudPacked field datatype "FLOAT32");
- numeric arrays may be given as 1-D numpy arrays: they travel as raw little-endian bytes (an extension type
  holding the dtype) and decode as read-only numpy arrays of the same dtype; lists stay lists. Consumers
  therefore accept both (`np.asarray`), and never test an array's truth value.

Message layouts used by diffctl:
  gz.msgs.Clock      {"header": H, "sim": T, "real": T, "system": T}
  gz.msgs.Twist      {"header": H, "linear": V3, "angular": V3}
  gz.msgs.Odometry   {"header": H, "pose": {"position": V3, "orientation": Q}, "twist": {"linear": V3, "angular": V3}}
  gz.msgs.Model      {"header": H, "name": str, "joint": [{"name": str, "axis1": {"position": f, "velocity": f,
                      "force": f}}]}   (JointStatePublisher output)
  gz.msgs.Pose       {"header": H, "name": str, "position": V3, "orientation": Q}
  gz.msgs.Pose_V     {"header": H, "pose": [gz.msgs.Pose]}  (each pose's header names frame_id / child_frame_id)
  gz.msgs.LaserScan  {"header": H, "frame": str, "world_pose": P, "angle_min": f, "angle_max": f,
                      "angle_step": f, "range_min": f, "range_max": f, "count": n, "vertical_angle_min": f,
                      "vertical_angle_max": f, "vertical_angle_step": f, "vertical_count": n,
                      "ranges": [f], "intensities": [f]}
  gz.msgs.IMU        {"header": H, "entity_name": str, "orientation": Q, "angular_velocity": V3,
                      "linear_acceleration": V3, "orientation_covariance": {"data": [9 f]}, ...}
  gz.msgs.Image      {"header": H, "width": n, "height": n, "step": n, "pixel_format_type": "RGB_INT8",
                      "data": bytes}
  gz.msgs.CameraInfo {"header": H, "width": n, "height": n, "distortion": {"model": "PLUMB_BOB", "k": [f]},
                      "intrinsics": {"k": [9 f]}, "projection": {"p": [12 f]}, "rectification_matrix": [9 f]}
  gz.msgs.PointCloudPacked {"header": H, "field": [{"name": str, "offset": n, "datatype": "FLOAT32",
                      "count": n}], "height": n, "width": n, "is_bigendian": b, "point_step": n, "row_step": n,
                      "data": bytes, "is_dense": b}
  gz.msgs.NavSat     {"header": H, "latitude_deg": f, "longitude_deg": f, "altitude": f, "frame_id": str, ...}
  gz.msgs.Magnetometer {"header": H, "field_tesla": V3}      gz.msgs.FluidPressure {"header": H, "pressure": f,
                      "variance": f}
  scalars            {"header": H, "data": value}  (Double, Float, Boolean, Int32, StringMsg); Empty {}
  where H = {"stamp": T, "data": [{"key": "frame_id", "value": [str]}, {"key": "child_frame_id", ...}]},
        T = {"sec": int, "nsec": int}, V3 = {"x","y","z"}, Q = {"x","y","z","w"}, P = {"position", "orientation"}.
"""

from __future__ import annotations

from typing import Any

import msgpack
import numpy as np

from diffctl.errors import MessageError

PREFIX = "gz"
# MessagePack extension type of a numeric array: one byte naming the dtype, then its little-endian bytes.
ARRAY_EXT = 1
_DTYPES: tuple[np.dtype, ...] = tuple(
    np.dtype(t).newbyteorder("<") for t in ("f4", "f8", "i1", "i2", "i4", "i8", "u1", "u2", "u4", "u8", "bool")
)
_DTYPE_CODE = {dt: i for i, dt in enumerate(_DTYPES)}


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


# Liveliness tokens of gz-side endpoints, so `gz topic -l/-i` can list them (gz-transport's discovery):
# `gz_lv/<pub|sub>/<session zid>/<topic with / as %>/<gz type>`.
ENDPOINT_TOKEN_PREFIX = "gz_lv"


def endpoint_token(kind: str, zid: str, topic: str, gz_type: str) -> str:
    return f"{ENDPOINT_TOKEN_PREFIX}/{kind}/{zid}/{key(topic)[len(PREFIX) + 1 :].replace('/', '%')}/{gz_type}"


def announce(session: Any, kind: str, topic: str, gz_type: str) -> Any:
    """The liveliness token that makes a gz-side publisher (`kind` "pub") or subscriber ("sub") of `session`
    discoverable, as gz-transport advertises its endpoints; undeclare it when the endpoint goes."""
    return session.liveliness().declare_token(endpoint_token(kind, str(session.zid()), topic, gz_type))


# gz-side services (gz-transport's Advertise of a service): a queryable on `gz_srv/<name>` taking one sample
# of the request type and answering one of the response type, in this encoding; announced by an endpoint token
# of kind "srv" whose type is `<request type>~<response type>`.
SERVICE_PREFIX = "gz_srv"


def service_key(name: str) -> str:
    return SERVICE_PREFIX + key(name)[len(PREFIX) :]


def announce_service(session: Any, name: str, request_type: str, response_type: str) -> Any:
    return announce(session, "srv", name, f"{request_type}~{response_type}")


def parse_endpoint_token(token_key: str) -> tuple[str, str, str, str] | None:
    """(kind, zid, topic, gz type) of an endpoint token key, or None."""
    parts = str(token_key).split("/")
    if len(parts) != 5 or parts[0] != ENDPOINT_TOKEN_PREFIX:
        return None
    return parts[1], parts[2], "/" + parts[3].replace("%", "/"), parts[4]


def _default(obj: Any) -> Any:
    # Called by msgpack only for what it cannot pack natively.
    if isinstance(obj, np.ndarray):
        dt = obj.dtype.newbyteorder("<") if obj.dtype.byteorder != "|" else obj.dtype
        code = _DTYPE_CODE.get(dt)
        if code is None:
            raise TypeError(f"numpy array of dtype {obj.dtype} has no gz encoding; valid: {_DTYPES}")
        return msgpack.ExtType(ARRAY_EXT, bytes((code,)) + np.ascontiguousarray(obj.ravel(), dtype=dt).tobytes())
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, (bytearray, memoryview)):
        return bytes(obj)
    raise TypeError(f"cannot encode {type(obj).__name__} in a gz message")


def _ext_hook(code: int, data: bytes) -> Any:
    if code != ARRAY_EXT or not data or data[0] >= len(_DTYPES):
        raise ValueError(f"unknown extension type {code}")
    dt = _DTYPES[data[0]]
    if (len(data) - 1) % dt.itemsize:
        raise ValueError(f"array of {dt} with {len(data) - 1} bytes")
    return np.frombuffer(data, dtype=dt, offset=1)


def encode(gz_type: str, msg: dict[str, Any]) -> bytes:
    """One sample: fields of `gz_type` (see the module docstring) → bytes. Raises MessageError for values
    that have no encoding."""
    try:
        return msgpack.packb((gz_type, msg), default=_default, use_bin_type=True)
    except (TypeError, ValueError, OverflowError) as e:
        raise MessageError(f"cannot encode {gz_type}: {e}") from None


def decode(payload: bytes | bytearray | memoryview, expected_type: str | None = None) -> tuple[str, dict[str, Any]]:
    """(type, fields) of a gz sample; raises MessageError on malformed data or an unexpected type."""
    try:
        obj = msgpack.unpackb(payload, ext_hook=_ext_hook, raw=False, strict_map_key=True, use_list=True)
    except Exception as e:  # msgpack raises a family of errors (ExtraData, FormatError, StackError, ValueError...)
        raise MessageError(f"malformed gz message: {type(e).__name__}: {e}") from None
    if not (isinstance(obj, list) and len(obj) == 2 and isinstance(obj[0], str) and isinstance(obj[1], dict)):
        raise MessageError("malformed gz message: not a [type, fields] pair")
    gz_type, fields = obj
    if expected_type is not None and gz_type != expected_type:
        raise MessageError(f"gz message of type {gz_type}, expected {expected_type}")
    return gz_type, fields


def clock(sim_ns: int, real_ns: int, system_ns: int) -> bytes:
    """gz.msgs.Clock, the hottest sample (100 per sim second, thousands per wall second at rtf 0)."""
    s, r, w = divmod(sim_ns, 1_000_000_000), divmod(real_ns, 1_000_000_000), divmod(system_ns, 1_000_000_000)
    return msgpack.packb(
        (
            "gz.msgs.Clock",
            {
                "header": {"stamp": {"sec": s[0], "nsec": s[1]}, "data": []},
                "sim": {"sec": s[0], "nsec": s[1]},
                "real": {"sec": r[0], "nsec": r[1]},
                "system": {"sec": w[0], "nsec": w[1]},
            },
        ),
        use_bin_type=True,
    )


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
