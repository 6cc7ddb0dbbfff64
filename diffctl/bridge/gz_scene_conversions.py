"""ros_gz_interfaces' scene and GUI messages as ros_gz_bridge converts them (ros_gz_bridge/src/convert/
ros_gz_interfaces.cpp, jazzy): Light, MaterialColor, SensorNoise, TrackVisual, GuiCamera ↔ GUICamera,
VideoRecord.

gz enums travel by name: Light.type POINT|SPOT|DIRECTIONAL (ROS 0|1|2), MaterialColor.entity_match FIRST|ALL
(0|1), SensorNoise.type NONE|GAUSSIAN|GAUSSIAN_QUANTIZED (ROS 0|2|3). A value ros_gz_bridge does not map leaves
the other side's field at its default, as it does. SensorNoise's dynamic_bias_correlation_time is not
converted (ros_gz_bridge leaves it out).
"""

from __future__ import annotations

from typing import Any

from diffctl.bridge.conversions import (
    GzDict,
    float32_field,
    float_field,
    header_to_gz,
    header_to_ros,
    make_msg,
    pose_fields_to_gz,
    pose_to_ros,
    vector3_to_gz,
    vector3_to_ros,
)
from diffctl.bridge.gz_interfaces_conversions import entity_to_gz, entity_to_ros
from diffctl.bridge.std_conversions import color_to_gz, color_to_ros

LIGHT_TYPES = ("POINT", "SPOT", "DIRECTIONAL")
ENTITY_MATCH = ("FIRST", "ALL")
NOISE_TYPES = {"NONE": 0, "GAUSSIAN": 2, "GAUSSIAN_QUANTIZED": 3}


def _index(names: tuple[str, ...], value: Any, default: int = 0) -> int:
    if isinstance(value, int):
        return value if 0 <= value < len(names) else default
    return names.index(value) if value in names else default


def light_to_ros(m: GzDict) -> Any:
    return make_msg(
        "ros_gz_interfaces/msg/Light",
        header=header_to_ros(m.get("header")),
        name=str(m.get("name", "")),
        type=_index(LIGHT_TYPES, m.get("type", "POINT")),
        pose=pose_to_ros(m.get("pose")),
        diffuse=color_to_ros(m.get("diffuse") or {}),
        specular=color_to_ros(m.get("specular") or {}),
        attenuation_constant=float32_field(m, "attenuation_constant"),
        attenuation_linear=float32_field(m, "attenuation_linear"),
        attenuation_quadratic=float32_field(m, "attenuation_quadratic"),
        direction=vector3_to_ros(m.get("direction")),
        range=float32_field(m, "range"),
        cast_shadows=bool(m.get("cast_shadows", False)),
        spot_inner_angle=float32_field(m, "spot_inner_angle"),
        spot_outer_angle=float32_field(m, "spot_outer_angle"),
        spot_falloff=float32_field(m, "spot_falloff"),
        id=int(m.get("id", 0)),
        parent_id=int(m.get("parent_id", 0)),
        intensity=float32_field(m, "intensity"),
    )


def light_to_gz(msg: Any) -> GzDict:
    out: GzDict = {
        "header": header_to_gz(msg.header),
        "name": msg.name,
        "pose": pose_fields_to_gz(msg.pose),
        "diffuse": color_to_gz(msg.diffuse),
        "specular": color_to_gz(msg.specular),
        "attenuation_constant": float(msg.attenuation_constant),
        "attenuation_linear": float(msg.attenuation_linear),
        "attenuation_quadratic": float(msg.attenuation_quadratic),
        "direction": vector3_to_gz(msg.direction),
        "range": float(msg.range),
        "cast_shadows": bool(msg.cast_shadows),
        "spot_inner_angle": float(msg.spot_inner_angle),
        "spot_outer_angle": float(msg.spot_outer_angle),
        "spot_falloff": float(msg.spot_falloff),
        "id": int(msg.id),
        "parent_id": int(msg.parent_id),
        "intensity": float(msg.intensity),
    }
    if int(msg.type) < len(LIGHT_TYPES):
        out["type"] = LIGHT_TYPES[int(msg.type)]
    return out


def material_color_to_ros(m: GzDict) -> Any:
    return make_msg(
        "ros_gz_interfaces/msg/MaterialColor",
        header=header_to_ros(m.get("header")),
        entity=entity_to_ros(m.get("entity")),
        ambient=color_to_ros(m.get("ambient") or {}),
        diffuse=color_to_ros(m.get("diffuse") or {}),
        specular=color_to_ros(m.get("specular") or {}),
        emissive=color_to_ros(m.get("emissive") or {}),
        shininess=float_field(m, "shininess"),
        entity_match=_index(ENTITY_MATCH, m.get("entity_match", "FIRST")),
    )


def material_color_to_gz(msg: Any) -> GzDict:
    out: GzDict = {
        "header": header_to_gz(msg.header),
        "entity": entity_to_gz(msg.entity),
        "ambient": color_to_gz(msg.ambient),
        "diffuse": color_to_gz(msg.diffuse),
        "specular": color_to_gz(msg.specular),
        "emissive": color_to_gz(msg.emissive),
        "shininess": float(msg.shininess),
    }
    if int(msg.entity_match) < len(ENTITY_MATCH):
        out["entity_match"] = ENTITY_MATCH[int(msg.entity_match)]
    return out


def sensor_noise_to_ros(m: GzDict) -> Any:
    return make_msg(
        "ros_gz_interfaces/msg/SensorNoise",
        header=header_to_ros(m.get("header")),
        type=NOISE_TYPES.get(str(m.get("type", "NONE")), 0),
        mean=float_field(m, "mean"),
        stddev=float_field(m, "stddev"),
        bias_mean=float_field(m, "bias_mean"),
        bias_stddev=float_field(m, "bias_stddev"),
        precision=float_field(m, "precision"),
        dynamic_bias_stddev=float_field(m, "dynamic_bias_stddev"),
        dynamic_bias_correlation_time=0.0,
    )


def sensor_noise_to_gz(msg: Any) -> GzDict:
    out: GzDict = {
        "header": header_to_gz(msg.header),
        "mean": float(msg.mean),
        "stddev": float(msg.stddev),
        "bias_mean": float(msg.bias_mean),
        "bias_stddev": float(msg.bias_stddev),
        "precision": float(msg.precision),
        "dynamic_bias_stddev": float(msg.dynamic_bias_stddev),
    }
    names = {v: k for k, v in NOISE_TYPES.items()}
    if int(msg.type) in names:
        out["type"] = names[int(msg.type)]
    return out


def track_visual_to_ros(m: GzDict) -> Any:
    return make_msg(
        "ros_gz_interfaces/msg/TrackVisual",
        header=header_to_ros(m.get("header")),
        name=str(m.get("name", "")),
        id=int(m.get("id", 0)),
        inherit_orientation=bool(m.get("inherit_orientation", False)),
        min_dist=float_field(m, "min_dist"),
        max_dist=float_field(m, "max_dist"),
        is_static=bool(m.get("static", False)),
        use_model_frame=bool(m.get("use_model_frame", False)),
        xyz=vector3_to_ros(m.get("xyz")),
        inherit_yaw=bool(m.get("inherit_yaw", False)),
    )


def track_visual_to_gz(msg: Any) -> GzDict:
    return {
        "header": header_to_gz(msg.header),
        "name": msg.name,
        "id": int(msg.id),
        "inherit_orientation": bool(msg.inherit_orientation),
        "min_dist": float(msg.min_dist),
        "max_dist": float(msg.max_dist),
        "static": bool(msg.is_static),
        "use_model_frame": bool(msg.use_model_frame),
        "xyz": vector3_to_gz(msg.xyz),
        "inherit_yaw": bool(msg.inherit_yaw),
    }


def gui_camera_to_ros(m: GzDict) -> Any:
    return make_msg(
        "ros_gz_interfaces/msg/GuiCamera",
        header=header_to_ros(m.get("header")),
        name=str(m.get("name", "")),
        view_controller=str(m.get("view_controller", "")),
        pose=pose_to_ros(m.get("pose")),
        track=track_visual_to_ros(m.get("track") or {}),
        projection_type=str(m.get("projection_type", "")),
    )


def gui_camera_to_gz(msg: Any) -> GzDict:
    return {
        "header": header_to_gz(msg.header),
        "name": msg.name,
        "view_controller": msg.view_controller,
        "pose": pose_fields_to_gz(msg.pose),
        "track": track_visual_to_gz(msg.track),
        "projection_type": msg.projection_type,
    }


def video_record_to_ros(m: GzDict) -> Any:
    return make_msg(
        "ros_gz_interfaces/msg/VideoRecord",
        header=header_to_ros(m.get("header")),
        start=bool(m.get("start", False)),
        stop=bool(m.get("stop", False)),
        format=str(m.get("format", "")),
        save_filename=str(m.get("save_filename", "")),
    )


def video_record_to_gz(msg: Any) -> GzDict:
    return {
        "header": header_to_gz(msg.header),
        "start": bool(msg.start),
        "stop": bool(msg.stop),
        "format": msg.format,
        "save_filename": msg.save_filename,
    }
