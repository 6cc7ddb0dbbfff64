"""Pure conversions between gz.msgs sensor dicts and sensor_msgs messages, following ros_gz_bridge.

Upstream rules (ros_gz_bridge `src/convert/sensor_msgs.cpp`) kept here: the LaserScan frame comes from its
`frame` field and a multi-layer scan keeps its middle layer; Image pixel formats map to ROS encodings with
`step = width · channels · bytes`; CameraInfo distortion models map to plumb_bob / rational_polynomial /
equidistant with d = distortion.k and K, R, P copied element by element; PointCloudPacked ↔ PointCloud2 is a
one-to-one copy; IMU covariances are copied when they have 9 elements; NavSat's frame comes from its
`frame_id` field. Where upstream silently truncates or keeps a default, a sample that cannot be represented
(unknown pixel format, wrong data length, too many matrix elements) raises MessageError, so the bridge drops
it with a warning instead of publishing something wrong.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from diffctl.bridge.conversions import (
    GzDict,
    float32_field,
    float_field,
    frame_to_ros,
    header_to_gz,
    header_to_ros,
    make_msg,
    quaternion_to_gz,
    quaternion_to_ros,
    vector3_to_gz,
    vector3_to_ros,
    zero_covariance,
)
from diffctl.errors import MessageError
from diffctl.interfaces import types


def _array(m: GzDict, name: str, dtype: type) -> np.ndarray:
    # A repeated field arrives as a list or, packed by the producer, as a numpy array (see diffctl/bus/gz.py).
    value = m.get(name)
    return np.asarray([] if value is None else value, dtype=dtype)


def _bytes(m: GzDict, name: str, what: str) -> bytes:
    value = m.get(name, b"")
    if not isinstance(value, (bytes, bytearray, memoryview)):
        raise MessageError(f"{what}.{name} must be raw bytes, got {type(value).__name__}")
    return bytes(value)


def _fixed(values: np.ndarray, n: int, what: str) -> np.ndarray:
    # ROS fixed-size arrays (K, R, P): fewer gz elements leave zeros, as upstream's element copy does.
    if len(values) > n:
        raise MessageError(f"{what} has {len(values)} elements, at most {n} fit")
    out = np.zeros(n, dtype=np.float64)
    out[: len(values)] = values
    return out


# --- sensor_msgs/msg/LaserScan <-> gz.msgs.LaserScan ------------------------------------------------------


def laser_scan_to_ros(m: GzDict) -> Any:
    header = header_to_ros(m.get("header"))
    if m.get("frame"):
        header.frame_id = frame_to_ros(str(m["frame"]))
    ranges = _array(m, "ranges", np.float32)
    intensities = _array(m, "intensities", np.float32)
    count = int(m.get("count") or len(ranges))
    vcount = int(m.get("vertical_count") or 1)
    if vcount > 1 and len(ranges) >= count * vcount:
        # A multi-layer scan becomes its middle layer, as ros_gz_bridge does.
        start = (vcount // 2) * count
        ranges = ranges[start : start + count]
        intensities = intensities[start : start + count] if len(intensities) >= start + count else intensities[:0]
    return make_msg(
        "sensor_msgs/msg/LaserScan",
        header=header,
        angle_min=float32_field(m, "angle_min"),
        angle_max=float32_field(m, "angle_max"),
        angle_increment=float32_field(m, "angle_step"),
        time_increment=0.0,
        scan_time=0.0,
        range_min=float32_field(m, "range_min"),
        range_max=float32_field(m, "range_max"),
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
        "ranges": np.asarray(msg.ranges, dtype=np.float64),
        "intensities": np.asarray(msg.intensities, dtype=np.float64),
    }


# --- sensor_msgs/msg/Imu <-> gz.msgs.IMU ------------------------------------------------------------------

_IMU_COVARIANCES = ("orientation_covariance", "angular_velocity_covariance", "linear_acceleration_covariance")


def imu_to_ros(m: GzDict) -> Any:
    covariances = {}
    for name in _IMU_COVARIANCES:
        values = _array(m.get(name) or {}, "data", np.float64)
        covariances[name] = values.copy() if len(values) == 9 else zero_covariance(9)
    return make_msg(
        "sensor_msgs/msg/Imu",
        header=header_to_ros(m.get("header")),
        orientation=quaternion_to_ros(m.get("orientation")),
        angular_velocity=vector3_to_ros(m.get("angular_velocity")),
        linear_acceleration=vector3_to_ros(m.get("linear_acceleration")),
        **covariances,
    )


def imu_to_gz(msg: Any) -> GzDict:
    return {
        "header": header_to_gz(msg.header),
        "entity_name": msg.header.frame_id,
        "orientation": quaternion_to_gz(msg.orientation),
        "angular_velocity": vector3_to_gz(msg.angular_velocity),
        "linear_acceleration": vector3_to_gz(msg.linear_acceleration),
        **{name: {"data": np.asarray(getattr(msg, name), dtype=np.float64)} for name in _IMU_COVARIANCES},
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
    "BGR_INT16": ("bgr16", 6),
    "R_FLOAT32": ("32FC1", 4),
    "RGB_FLOAT32": ("32FC3", 12),
    "BAYER_RGGB8": ("bayer_rggb8", 1),
    "BAYER_BGGR8": ("bayer_bggr8", 1),
    "BAYER_GBRG8": ("bayer_gbrg8", 1),
    "BAYER_GRBG8": ("bayer_grbg8", 1),
}
# ROS encodings → gz pixel format; the OpenCV-style names of single-channel images are the same layouts.
ENCODINGS = {enc: fmt for fmt, (enc, _) in PIXEL_FORMATS.items()} | {
    "8UC1": "L_INT8",
    "16UC1": "L_INT16",
    "8UC3": "RGB_INT8",
    "8UC4": "RGBA_INT8",
}


def image_to_ros(m: GzDict) -> Any:
    fmt = str(m.get("pixel_format_type") or "UNKNOWN_PIXEL_FORMAT")
    if fmt not in PIXEL_FORMATS:
        raise MessageError(f"gz.msgs.Image pixel_format_type {fmt!r} unsupported; valid: {', '.join(PIXEL_FORMATS)}")
    encoding, bpp = PIXEL_FORMATS[fmt]
    width, height = int(m.get("width", 0)), int(m.get("height", 0))
    step = int(m.get("step") or width * bpp)
    if step < width * bpp:
        raise MessageError(f"gz.msgs.Image step {step} is shorter than width {width} x {bpp} bytes ({fmt})")
    data = _bytes(m, "data", "gz.msgs.Image")
    if len(data) != step * height:
        raise MessageError(f"gz.msgs.Image data has {len(data)} bytes, expected step {step} x height {height}")
    return make_msg(
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
    data = np.asarray(msg.data, dtype=np.uint8).tobytes()
    if len(data) != int(msg.step) * int(msg.height):
        raise MessageError(f"image data has {len(data)} bytes, expected step {msg.step} x height {msg.height}")
    return {
        "header": header_to_gz(msg.header),
        "width": int(msg.width),
        "height": int(msg.height),
        "step": int(msg.step),
        "pixel_format_type": ENCODINGS[msg.encoding],
        "data": data,
    }


# --- sensor_msgs/msg/CameraInfo <-> gz.msgs.CameraInfo ----------------------------------------------------

DISTORTION_MODELS = {
    "PLUMB_BOB": "plumb_bob",
    "RATIONAL_POLYNOMIAL": "rational_polynomial",
    "EQUIDISTANT": "equidistant",
}
_GZ_DISTORTION = {ros: gz_name for gz_name, ros in DISTORTION_MODELS.items()}


def camera_info_to_ros(m: GzDict) -> Any:
    distortion = m.get("distortion")
    model, d = "", np.zeros(0, dtype=np.float64)
    if distortion is not None:
        # protobuf's default enum value (0) is PLUMB_BOB: an absent model name means it.
        name = str(distortion.get("model") or "PLUMB_BOB")
        if name not in DISTORTION_MODELS:
            raise MessageError(
                f"gz.msgs.CameraInfo distortion model {name!r} unsupported; valid: {', '.join(DISTORTION_MODELS)}"
            )
        model, d = DISTORTION_MODELS[name], _array(distortion, "k", np.float64).copy()
    return make_msg(
        "sensor_msgs/msg/CameraInfo",
        header=header_to_ros(m.get("header")),
        height=int(m.get("height", 0)),
        width=int(m.get("width", 0)),
        distortion_model=model,
        d=d,
        k=_fixed(_array(m.get("intrinsics") or {}, "k", np.float64), 9, "gz.msgs.CameraInfo intrinsics.k"),
        r=_fixed(_array(m, "rectification_matrix", np.float64), 9, "gz.msgs.CameraInfo rectification_matrix"),
        p=_fixed(_array(m.get("projection") or {}, "p", np.float64), 12, "gz.msgs.CameraInfo projection.p"),
        binning_x=0,
        binning_y=0,
        roi=make_msg("sensor_msgs/msg/RegionOfInterest", x_offset=0, y_offset=0, height=0, width=0, do_rectify=False),
    )


def camera_info_to_gz(msg: Any) -> GzDict:
    if msg.distortion_model not in _GZ_DISTORTION:
        raise MessageError(
            f"distortion_model {msg.distortion_model!r} has no gz equivalent; valid: {', '.join(_GZ_DISTORTION)}"
        )
    return {
        "header": header_to_gz(msg.header),
        "width": int(msg.width),
        "height": int(msg.height),
        "distortion": {"model": _GZ_DISTORTION[msg.distortion_model], "k": np.asarray(msg.d, dtype=np.float64)},
        "intrinsics": {"k": np.asarray(msg.k, dtype=np.float64)},
        "projection": {"p": np.asarray(msg.p, dtype=np.float64)},
        "rectification_matrix": np.asarray(msg.r, dtype=np.float64),
    }


# --- sensor_msgs/msg/PointCloud2 <-> gz.msgs.PointCloudPacked ---------------------------------------------

# gz.msgs.PointCloudPacked.Field.DataType names, in sensor_msgs/PointField order (INT8 = 1 … FLOAT64 = 8).
POINT_DATATYPES = ("INT8", "UINT8", "INT16", "UINT16", "INT32", "UINT32", "FLOAT32", "FLOAT64")


def point_cloud_to_ros(m: GzDict) -> Any:
    fields = []
    for f in m.get("field") or []:
        datatype = str(f.get("datatype") or "INT8")  # protobuf's default enum value
        if datatype not in POINT_DATATYPES:
            raise MessageError(
                f"gz.msgs.PointCloudPacked field {f.get('name')!r} datatype {datatype!r} unsupported; "
                f"valid: {', '.join(POINT_DATATYPES)}"
            )
        fields.append(
            make_msg(
                "sensor_msgs/msg/PointField",
                name=str(f.get("name", "")),
                offset=int(f.get("offset", 0)),
                datatype=POINT_DATATYPES.index(datatype) + 1,
                count=int(f.get("count", 0)),
            )
        )
    height, row_step = int(m.get("height", 0)), int(m.get("row_step", 0))
    data = _bytes(m, "data", "gz.msgs.PointCloudPacked")
    if len(data) != row_step * height:
        raise MessageError(
            f"gz.msgs.PointCloudPacked data has {len(data)} bytes, expected row_step {row_step} x height {height}"
        )
    return make_msg(
        "sensor_msgs/msg/PointCloud2",
        header=header_to_ros(m.get("header")),
        height=height,
        width=int(m.get("width", 0)),
        fields=fields,
        is_bigendian=bool(m.get("is_bigendian", False)),
        point_step=int(m.get("point_step", 0)),
        row_step=row_step,
        data=np.frombuffer(data, dtype=np.uint8),
        is_dense=bool(m.get("is_dense", False)),
    )


def point_cloud_to_gz(msg: Any) -> GzDict:
    fields = []
    for f in msg.fields:
        if not 1 <= f.datatype <= len(POINT_DATATYPES):
            raise MessageError(f"PointField {f.name!r} datatype {f.datatype} invalid; valid: 1 (INT8) … 8 (FLOAT64)")
        fields.append(
            {
                "name": f.name,
                "offset": int(f.offset),
                "datatype": POINT_DATATYPES[f.datatype - 1],
                "count": int(f.count),
            }
        )
    return {
        "header": header_to_gz(msg.header),
        "field": fields,
        "height": int(msg.height),
        "width": int(msg.width),
        "is_bigendian": bool(msg.is_bigendian),
        "point_step": int(msg.point_step),
        "row_step": int(msg.row_step),
        "data": np.asarray(msg.data, dtype=np.uint8).tobytes(),
        "is_dense": bool(msg.is_dense),
    }


# --- sensor_msgs/msg/NavSatFix <-> gz.msgs.NavSat ---------------------------------------------------------


def nav_sat_to_ros(m: GzDict) -> Any:
    header = header_to_ros(m.get("header"))
    header.frame_id = frame_to_ros(str(m.get("frame_id", "")))
    status = types.get_class("sensor_msgs/msg/NavSatStatus")
    fix = types.get_class("sensor_msgs/msg/NavSatFix")
    return make_msg(
        "sensor_msgs/msg/NavSatFix",
        header=header,
        # NavSat carries no fix status or covariance: a fix, covariance unknown (as ros_gz_bridge).
        status=status(status=status.STATUS_FIX, service=status.SERVICE_UNKNOWN),
        latitude=float_field(m, "latitude_deg"),
        longitude=float_field(m, "longitude_deg"),
        altitude=float_field(m, "altitude"),
        position_covariance=zero_covariance(9),
        position_covariance_type=fix.COVARIANCE_TYPE_UNKNOWN,
    )


def nav_sat_fix_to_gz(msg: Any) -> GzDict:
    return {
        "header": header_to_gz(msg.header),
        "latitude_deg": float(msg.latitude),
        "longitude_deg": float(msg.longitude),
        "altitude": float(msg.altitude),
        "frame_id": msg.header.frame_id,
        "velocity_east": 0.0,
        "velocity_north": 0.0,
        "velocity_up": 0.0,
    }


# --- sensor_msgs/msg/MagneticField <-> gz.msgs.Magnetometer, FluidPressure <-> gz.msgs.FluidPressure --------


def magnetometer_to_ros(m: GzDict) -> Any:
    return make_msg(
        "sensor_msgs/msg/MagneticField",
        header=header_to_ros(m.get("header")),
        magnetic_field=vector3_to_ros(m.get("field_tesla")),
        magnetic_field_covariance=zero_covariance(9),
    )


def magnetic_field_to_gz(msg: Any) -> GzDict:
    return {"header": header_to_gz(msg.header), "field_tesla": vector3_to_gz(msg.magnetic_field)}


def fluid_pressure_to_ros(m: GzDict) -> Any:
    return make_msg(
        "sensor_msgs/msg/FluidPressure",
        header=header_to_ros(m.get("header")),
        fluid_pressure=float_field(m, "pressure"),
        variance=float_field(m, "variance"),
    )


def fluid_pressure_to_gz(msg: Any) -> GzDict:
    return {
        "header": header_to_gz(msg.header),
        "pressure": float(msg.fluid_pressure),
        "variance": float(msg.variance),
    }


# gz.msgs.BatteryState.PowerSupplyStatus names in sensor_msgs' POWER_SUPPLY_STATUS_* order (0..4).
BATTERY_STATUSES = ("UNKNOWN", "CHARGING", "DISCHARGING", "NOT_CHARGING", "FULL")


def battery_state_to_ros(m: GzDict) -> Any:
    status = m.get("power_supply_status", "UNKNOWN")
    if isinstance(status, int):
        status = BATTERY_STATUSES[status] if 0 <= status < len(BATTERY_STATUSES) else "UNKNOWN"
    if status not in BATTERY_STATUSES:
        raise MessageError(f"BatteryState power_supply_status {status!r} is not one of {', '.join(BATTERY_STATUSES)}")
    return make_msg(
        "sensor_msgs/msg/BatteryState",
        header=header_to_ros(m.get("header")),
        voltage=float32_field(m, "voltage"),
        temperature=0.0,  # the other fields keep the ROS message's defaults, as ros_gz_bridge leaves them
        current=float32_field(m, "current"),
        charge=float32_field(m, "charge"),
        capacity=float32_field(m, "capacity"),
        # ros_gz_bridge: the design capacity is not known on the gz side
        design_capacity=math.nan,
        percentage=float32_field(m, "percentage"),
        power_supply_status=BATTERY_STATUSES.index(status),
        power_supply_health=0,
        power_supply_technology=0,
        present=False,
        cell_voltage=np.zeros(0, dtype=np.float32),
        cell_temperature=np.zeros(0, dtype=np.float32),
        location="",
        serial_number="",
    )


def battery_state_to_gz(msg: Any) -> GzDict:
    status = int(msg.power_supply_status)
    if not 0 <= status < len(BATTERY_STATUSES):
        raise MessageError(f"BatteryState power_supply_status {status} is not 0..{len(BATTERY_STATUSES) - 1}")
    return {
        "header": header_to_gz(msg.header),
        "voltage": float(msg.voltage),
        "current": float(msg.current),
        "charge": float(msg.charge),
        "capacity": float(msg.capacity),
        "percentage": float(msg.percentage),
        "power_supply_status": BATTERY_STATUSES[status],
    }
