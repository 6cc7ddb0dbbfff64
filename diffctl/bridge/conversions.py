"""Pure conversions between simulator-side gz.msgs dicts (layouts in diffctl/bus/gz.py) and ROS messages.

Each supported pair has `<name>_to_ros(gz_dict) -> msg` and `<name>_to_gz(msg) -> gz_dict`; the behaviour
follows ros_gz_bridge's convert functions (frame ids from the gz header's `frame_id` / `child_frame_id`
entries, `::` in gz scoped names becomes `/`, the middle vertical slice of a multi-layer scan). Nothing here
touches the bus: messages are built from the message classes of `diffctl.bus.types`.
"""

from __future__ import annotations

import base64
import math
from typing import Any

import numpy as np

from diffctl.bus import gz, types
from diffctl.errors import MessageError

GzDict = dict[str, Any]


def _msg(typename: str, **fields: Any) -> Any:
    return types.get_class(typename)(**fields)


# --- building blocks -------------------------------------------------------------------------------------


def frame_to_ros(name: str) -> str:
    # Gazebo scopes names with "::" (robot::lidar_link); ROS frame ids use "/".
    return name.replace("::", "/")


def time_to_ros(t: dict[str, Any] | None) -> Any:
    t = t or {}
    return _msg("builtin_interfaces/msg/Time", sec=int(t.get("sec", 0)), nanosec=int(t.get("nsec", 0)))


def time_to_gz(t: Any) -> dict[str, int]:
    return {"sec": int(t.sec), "nsec": int(t.nanosec)}


def header_to_ros(h: dict[str, Any] | None) -> Any:
    return _msg(
        "std_msgs/msg/Header",
        stamp=time_to_ros((h or {}).get("stamp")),
        frame_id=frame_to_ros(gz.header_value(h, "frame_id")),
    )


def header_to_gz(h: Any, child_frame_id: str | None = None) -> GzDict:
    data = [{"key": "frame_id", "value": [h.frame_id]}] if h.frame_id else []
    if child_frame_id:
        data.append({"key": "child_frame_id", "value": [child_frame_id]})
    return {"stamp": time_to_gz(h.stamp), "data": data}


def _f(d: dict[str, Any] | None, name: str, default: float = 0.0) -> float:
    return float((d or {}).get(name, default))


def _f32(d: dict[str, Any] | None, name: str) -> float:
    # float32 fields carry what the wire will carry, so a round trip compares equal.
    return float(np.float32(_f(d, name)))


def vector3_to_ros(v: dict[str, Any] | None, typename: str = "geometry_msgs/msg/Vector3") -> Any:
    return _msg(typename, x=_f(v, "x"), y=_f(v, "y"), z=_f(v, "z"))


def vector3_to_gz(v: Any) -> dict[str, float]:
    return {"x": float(v.x), "y": float(v.y), "z": float(v.z)}


def quaternion_to_ros(q: dict[str, Any] | None) -> Any:
    # protobuf's default for an absent quaternion is all zeros; gz treats a missing orientation as identity.
    w = _f(q, "w", 1.0 if not q else 0.0)
    return _msg("geometry_msgs/msg/Quaternion", x=_f(q, "x"), y=_f(q, "y"), z=_f(q, "z"), w=w)


def quaternion_to_gz(q: Any) -> dict[str, float]:
    return {"x": float(q.x), "y": float(q.y), "z": float(q.z), "w": float(q.w)}


def pose_to_ros(p: dict[str, Any] | None) -> Any:
    p = p or {}
    return _msg(
        "geometry_msgs/msg/Pose",
        position=vector3_to_ros(p.get("position"), "geometry_msgs/msg/Point"),
        orientation=quaternion_to_ros(p.get("orientation")),
    )


def pose_fields_to_gz(p: Any) -> GzDict:
    return {"position": vector3_to_gz(p.position), "orientation": quaternion_to_gz(p.orientation)}


def twist_to_ros(t: dict[str, Any] | None) -> Any:
    t = t or {}
    return _msg(
        "geometry_msgs/msg/Twist", linear=vector3_to_ros(t.get("linear")), angular=vector3_to_ros(t.get("angular"))
    )


def _require_finite(values: list[float], what: str) -> None:
    # A NaN or inf velocity or pose must never reach the physics: drop the message instead.
    if not all(math.isfinite(v) for v in values):
        raise MessageError(f"{what} with a non-finite value {values} dropped")


def _twist_fields_to_gz(t: Any, what: str) -> GzDict:
    lin, ang = vector3_to_gz(t.linear), vector3_to_gz(t.angular)
    _require_finite([*lin.values(), *ang.values()], what)
    return {"linear": lin, "angular": ang}


def _zero_covariance(n: int) -> np.ndarray:
    return np.zeros(n, dtype=np.float64)


# --- rosgraph_msgs/msg/Clock <-> gz.msgs.Clock -----------------------------------------------------------


def clock_to_ros(m: GzDict) -> Any:
    return _msg("rosgraph_msgs/msg/Clock", clock=time_to_ros(m.get("sim")))


def clock_to_gz(msg: Any) -> GzDict:
    t = time_to_gz(msg.clock)
    return {"header": {"stamp": dict(t), "data": []}, "sim": t}


# --- geometry_msgs/msg/Twist(Stamped) <-> gz.msgs.Twist ---------------------------------------------------


def twist_to_gz(msg: Any) -> GzDict:
    return _twist_fields_to_gz(msg, "geometry_msgs/msg/Twist")


def twist_stamped_to_ros(m: GzDict) -> Any:
    return _msg("geometry_msgs/msg/TwistStamped", header=header_to_ros(m.get("header")), twist=twist_to_ros(m))


def twist_stamped_to_gz(msg: Any) -> GzDict:
    return {"header": header_to_gz(msg.header), **_twist_fields_to_gz(msg.twist, "geometry_msgs/msg/TwistStamped")}


# --- nav_msgs/msg/Odometry <-> gz.msgs.Odometry -----------------------------------------------------------


def odometry_to_ros(m: GzDict) -> Any:
    h = m.get("header")
    return _msg(
        "nav_msgs/msg/Odometry",
        header=header_to_ros(h),
        child_frame_id=frame_to_ros(gz.header_value(h, "child_frame_id")),
        pose=_msg(
            "geometry_msgs/msg/PoseWithCovariance", pose=pose_to_ros(m.get("pose")), covariance=_zero_covariance(36)
        ),
        twist=_msg(
            "geometry_msgs/msg/TwistWithCovariance",
            twist=twist_to_ros(m.get("twist")),
            covariance=_zero_covariance(36),
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
        pos.append(_f(axis, "position"))
        vel.append(_f(axis, "velocity"))
        eff.append(_f(axis, "force"))
    return _msg(
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
            _msg(
                "geometry_msgs/msg/TransformStamped",
                header=_msg(
                    "std_msgs/msg/Header",
                    stamp=time_to_ros(stamp),
                    frame_id=frame_to_ros(gz.header_value(h, "frame_id")),
                ),
                child_frame_id=frame_to_ros(child),
                transform=_msg(
                    "geometry_msgs/msg/Transform",
                    translation=vector3_to_ros(p.get("position")),
                    rotation=quaternion_to_ros(p.get("orientation")),
                ),
            )
        )
    return _msg("tf2_msgs/msg/TFMessage", transforms=transforms)


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


# --- sensor_msgs/msg/LaserScan <-> gz.msgs.LaserScan ------------------------------------------------------


def laser_scan_to_ros(m: GzDict) -> Any:
    header = header_to_ros(m.get("header"))
    if m.get("frame"):
        header.frame_id = frame_to_ros(str(m["frame"]))
    ranges = np.asarray(m.get("ranges") or [], dtype=np.float32)
    intensities = np.asarray(m.get("intensities") or [], dtype=np.float32)
    count = int(m.get("count") or len(ranges))
    vcount = int(m.get("vertical_count") or 1)
    if vcount > 1 and len(ranges) >= count * vcount:
        # A multi-layer scan becomes its middle layer, as ros_gz_bridge does.
        start = (vcount // 2) * count
        ranges = ranges[start : start + count]
        intensities = intensities[start : start + count] if len(intensities) >= start + count else intensities[:0]
    return _msg(
        "sensor_msgs/msg/LaserScan",
        header=header,
        angle_min=_f32(m, "angle_min"),
        angle_max=_f32(m, "angle_max"),
        angle_increment=_f32(m, "angle_step"),
        time_increment=0.0,
        scan_time=0.0,
        range_min=_f32(m, "range_min"),
        range_max=_f32(m, "range_max"),
        ranges=ranges,
        intensities=intensities,
    )


def laser_scan_to_gz(msg: Any) -> GzDict:
    return {
        "header": header_to_gz(msg.header),
        "frame": msg.header.frame_id,
        "angle_min": float(msg.angle_min),
        "angle_max": float(msg.angle_max),
        "angle_step": float(msg.angle_increment),
        "range_min": float(msg.range_min),
        "range_max": float(msg.range_max),
        "count": len(msg.ranges),
        "vertical_count": 1,
        "ranges": np.asarray(msg.ranges, dtype=np.float64).tolist(),
        "intensities": np.asarray(msg.intensities, dtype=np.float64).tolist(),
    }


# --- sensor_msgs/msg/Imu <-> gz.msgs.IMU ------------------------------------------------------------------


def imu_to_ros(m: GzDict) -> Any:
    return _msg(
        "sensor_msgs/msg/Imu",
        header=header_to_ros(m.get("header")),
        orientation=quaternion_to_ros(m.get("orientation")),
        orientation_covariance=_zero_covariance(9),
        angular_velocity=vector3_to_ros(m.get("angular_velocity")),
        angular_velocity_covariance=_zero_covariance(9),
        linear_acceleration=vector3_to_ros(m.get("linear_acceleration")),
        linear_acceleration_covariance=_zero_covariance(9),
    )


def imu_to_gz(msg: Any) -> GzDict:
    return {
        "header": header_to_gz(msg.header),
        "entity_name": msg.header.frame_id,
        "orientation": quaternion_to_gz(msg.orientation),
        "angular_velocity": vector3_to_gz(msg.angular_velocity),
        "linear_acceleration": vector3_to_gz(msg.linear_acceleration),
    }


# --- sensor_msgs/msg/Image <-> gz.msgs.Image --------------------------------------------------------------

# gz.msgs.PixelFormatType ↔ sensor_msgs image encoding, with bytes per pixel.
PIXEL_FORMATS: dict[str, tuple[str, int]] = {
    "L_INT8": ("mono8", 1),
    "L_INT16": ("mono16", 2),
    "RGB_INT8": ("rgb8", 3),
    "RGBA_INT8": ("rgba8", 4),
    "BGR_INT8": ("bgr8", 3),
    "BGRA_INT8": ("bgra8", 4),
    "RGB_INT16": ("rgb16", 6),
    "R_FLOAT32": ("32FC1", 4),
    "RGB_FLOAT32": ("32FC3", 12),
    "BAYER_RGGB8": ("bayer_rggb8", 1),
    "BAYER_BGGR8": ("bayer_bggr8", 1),
    "BAYER_GBRG8": ("bayer_gbrg8", 1),
    "BAYER_GRBG8": ("bayer_grbg8", 1),
}
ENCODINGS = {enc: fmt for fmt, (enc, _) in PIXEL_FORMATS.items()}


def image_to_ros(m: GzDict) -> Any:
    fmt = str(m.get("pixel_format_type") or "RGB_INT8")
    if fmt not in PIXEL_FORMATS:
        raise MessageError(f"gz.msgs.Image pixel_format_type {fmt!r} unsupported; valid: {', '.join(PIXEL_FORMATS)}")
    encoding, bpp = PIXEL_FORMATS[fmt]
    width, height = int(m.get("width", 0)), int(m.get("height", 0))
    step = int(m.get("step") or width * bpp)
    raw = m.get("data") or ""
    data = base64.b64decode(raw, validate=True) if isinstance(raw, str) else bytes(raw)
    if len(data) != step * height:
        raise MessageError(f"gz.msgs.Image data has {len(data)} bytes, expected step {step} x height {height}")
    return _msg(
        "sensor_msgs/msg/Image",
        header=header_to_ros(m.get("header")),
        height=height,
        width=width,
        encoding=encoding,
        is_bigendian=0,
        step=step,
        data=np.frombuffer(data, dtype=np.uint8),
    )


def image_to_gz(msg: Any) -> GzDict:
    if msg.encoding not in ENCODINGS:
        raise MessageError(f"image encoding {msg.encoding!r} has no gz pixel format; valid: {', '.join(ENCODINGS)}")
    return {
        "header": header_to_gz(msg.header),
        "width": int(msg.width),
        "height": int(msg.height),
        "step": int(msg.step),
        "pixel_format_type": ENCODINGS[msg.encoding],
        "data": base64.b64encode(np.asarray(msg.data, dtype=np.uint8).tobytes()).decode("ascii"),
    }


# --- geometry_msgs/msg/Pose(Stamped) <-> gz.msgs.Pose -----------------------------------------------------


def pose_to_gz(msg: Any) -> GzDict:
    out = pose_fields_to_gz(msg)
    _require_finite([*out["position"].values(), *out["orientation"].values()], "geometry_msgs/msg/Pose")
    return out


def pose_stamped_to_ros(m: GzDict) -> Any:
    return _msg("geometry_msgs/msg/PoseStamped", header=header_to_ros(m.get("header")), pose=pose_to_ros(m))


def pose_stamped_to_gz(msg: Any) -> GzDict:
    return {"header": header_to_gz(msg.header), "name": "", **pose_to_gz(msg.pose)}


# --- std_msgs scalars <-> gz.msgs scalars -----------------------------------------------------------------


def scalar_to_ros(ros_type: str, cast: type) -> Any:
    def convert(m: GzDict) -> Any:
        return _msg(ros_type, data=cast(m.get("data", cast())))

    return convert


def scalar_to_gz(cast: type, finite: bool = False) -> Any:
    def convert(msg: Any) -> GzDict:
        value = cast(msg.data)
        if finite:
            _require_finite([value], "scalar command")
        return {"data": value}

    return convert
