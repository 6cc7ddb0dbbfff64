"""gps_msgs/GPSFix ↔ gz.msgs.NavSat and actuator_msgs/Actuators ↔ gz.msgs.Actuators, as ros_gz_bridge converts
them (ros_gz_bridge/src/convert/gps_msgs.cpp and actuator_msgs.cpp, jazzy).

gz layouts: NavSat `{"header", "latitude_deg", "longitude_deg", "altitude", "velocity_east", "velocity_north",
"velocity_up", "frame_id"}`; Actuators `{"header", "position": [f], "velocity": [f], "normalized": [f]}`.

GPSFix from gz: the horizontal velocity becomes speed and track (`atan2(north, east)`, radians from east, as
upstream, not a compass heading), climb the vertical one; a GBAS fix, covariance unknown; every other field
stays zero. To gz: the velocity from speed and track the same way, frame_id the header's.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from diffctl.bridge.conversions import GzDict, float_field, frame_to_ros, header_to_gz, header_to_ros
from diffctl.interfaces import types


def gps_fix_to_ros(m: GzDict) -> Any:
    msg = types.new("gps_msgs/msg/GPSFix")
    msg.header = header_to_ros(m.get("header"))
    msg.header.frame_id = frame_to_ros(str(m.get("frame_id", "")))
    msg.latitude = float_field(m, "latitude_deg")
    msg.longitude = float_field(m, "longitude_deg")
    msg.altitude = float_field(m, "altitude")
    east, north = float_field(m, "velocity_east"), float_field(m, "velocity_north")
    msg.speed = math.sqrt(east * east + north * north)
    msg.track = math.atan2(north, east)
    msg.climb = float_field(m, "velocity_up")
    msg.position_covariance_type = msg.COVARIANCE_TYPE_UNKNOWN
    msg.status.status = msg.status.STATUS_GBAS_FIX
    return msg


def gps_fix_to_gz(msg: Any) -> GzDict:
    track, speed = float(msg.track), float(msg.speed)
    return {
        "header": header_to_gz(msg.header),
        "latitude_deg": float(msg.latitude),
        "longitude_deg": float(msg.longitude),
        "altitude": float(msg.altitude),
        "frame_id": msg.header.frame_id,
        "velocity_east": math.cos(track) * speed,
        "velocity_north": math.sin(track) * speed,
        "velocity_up": float(msg.climb),
    }


def actuators_to_ros(m: GzDict) -> Any:
    msg = types.new("actuator_msgs/msg/Actuators")
    msg.header = header_to_ros(m.get("header"))
    for name in ("position", "velocity", "normalized"):
        setattr(msg, name, np.asarray(m.get(name, []), dtype=np.float64).reshape(-1).copy())
    return msg


def actuators_to_gz(msg: Any) -> GzDict:
    return {
        "header": header_to_gz(msg.header),
        **{name: [float(v) for v in getattr(msg, name)] for name in ("position", "velocity", "normalized")},
    }
