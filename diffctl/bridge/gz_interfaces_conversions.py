"""ros_gz_interfaces messages as ros_gz_bridge converts them (ros_gz_bridge/src/convert/ros_gz_interfaces.cpp,
jazzy): Altimeter, Entity, EntityWrench, JointWrench, Contact(s), Dataframe, Float32Array ↔ Float_V,
StringVec ↔ StringMsg_V, ParamVec ↔ Param / Param_V.

gz layouts: Altimeter `{"header", "vertical_position", "vertical_velocity", "vertical_reference"}`; Entity
`{"id", "name", "type": "NONE"|"LIGHT"|"MODEL"|"LINK"|"VISUAL"|"COLLISION"|"SENSOR"|"JOINT"}`; EntityWrench
`{"header", "entity", "wrench": {"force", "torque"}}`; JointWrench `{"header", "body_1_name", "body_1_id",
"body_2_name", "body_2_id", "body_1_wrench", "body_2_wrench"}`; Contact `{"collision1", "collision2",
"position": [V3], "normal": [V3], "depth": [f], "wrench": [JointWrench]}`; Contacts `{"header", "contact":
[Contact]}`; Dataframe `{"header" (rssi as a "rssi" header entry), "src_address", "dst_address", "data":
bytes}`; Float_V `{"data": [f]}`; StringMsg_V `{"header", "data": [str]}`; Param `{"header", "params": {name:
Any}, "children": [Param]}`; Param_V `{"header", "param": [Param]}`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from diffctl.bridge.conversions import (
    GzDict,
    float_field,
    header_to_gz,
    header_to_ros,
    make_msg,
    vector3_to_gz,
    vector3_to_ros,
)
from diffctl.bridge.geometry_conversions import wrench_to_gz, wrench_to_ros
from diffctl.bridge.std_conversions import any_to_parameter_value, parameter_value_to_any
from diffctl.bus import gz
from diffctl.errors import MessageError

# ros_gz_interfaces/msg/Entity's constants, in gz.msgs.Entity.Type's order
ENTITY_TYPES = ("NONE", "LIGHT", "MODEL", "LINK", "VISUAL", "COLLISION", "SENSOR", "JOINT")


def altimeter_to_ros(m: GzDict) -> Any:
    return make_msg(
        "ros_gz_interfaces/msg/Altimeter",
        header=header_to_ros(m.get("header")),
        vertical_position=float_field(m, "vertical_position"),
        vertical_velocity=float_field(m, "vertical_velocity"),
        vertical_reference=float_field(m, "vertical_reference"),
    )


def altimeter_to_gz(msg: Any) -> GzDict:
    return {
        "header": header_to_gz(msg.header),
        "vertical_position": float(msg.vertical_position),
        "vertical_velocity": float(msg.vertical_velocity),
        "vertical_reference": float(msg.vertical_reference),
    }


def entity_to_ros(m: GzDict | None) -> Any:
    m = m or {}
    kind = m.get("type", "NONE")
    if isinstance(kind, int):
        kind = ENTITY_TYPES[kind] if 0 <= kind < len(ENTITY_TYPES) else ""
    # ros_gz_bridge: an unknown gz type leaves the ROS type at its default (NONE)
    type_ = ENTITY_TYPES.index(kind) if kind in ENTITY_TYPES else 0
    return make_msg("ros_gz_interfaces/msg/Entity", id=int(m.get("id", 0)), name=str(m.get("name", "")), type=type_)


def entity_to_gz(msg: Any) -> GzDict:
    t = int(msg.type)
    # ros_gz_bridge: an unknown ROS type is reported and the gz type left unset (NONE)
    return {"id": int(msg.id), "name": str(msg.name), "type": ENTITY_TYPES[t] if t < len(ENTITY_TYPES) else "NONE"}


def entity_wrench_to_ros(m: GzDict) -> Any:
    return make_msg(
        "ros_gz_interfaces/msg/EntityWrench",
        header=header_to_ros(m.get("header")),
        entity=entity_to_ros(m.get("entity")),
        wrench=wrench_to_ros(m.get("wrench") or {}),
    )


def entity_wrench_to_gz(msg: Any) -> GzDict:
    return {"header": header_to_gz(msg.header), "entity": entity_to_gz(msg.entity), "wrench": wrench_to_gz(msg.wrench)}


def joint_wrench_to_ros(m: GzDict) -> Any:
    def string(v: Any) -> Any:
        return make_msg("std_msgs/msg/String", data=str(v or ""))

    def uint32(v: Any) -> Any:
        return make_msg("std_msgs/msg/UInt32", data=int(v or 0))

    return make_msg(
        "ros_gz_interfaces/msg/JointWrench",
        header=header_to_ros(m.get("header")),
        body_1_name=string(m.get("body_1_name")),
        body_1_id=uint32(m.get("body_1_id")),
        body_2_name=string(m.get("body_2_name")),
        body_2_id=uint32(m.get("body_2_id")),
        body_1_wrench=wrench_to_ros(m.get("body_1_wrench") or {}),
        body_2_wrench=wrench_to_ros(m.get("body_2_wrench") or {}),
    )


def joint_wrench_to_gz(msg: Any) -> GzDict:
    return {
        "header": header_to_gz(msg.header),
        "body_1_name": msg.body_1_name.data,
        "body_1_id": int(msg.body_1_id.data),
        "body_2_name": msg.body_2_name.data,
        "body_2_id": int(msg.body_2_id.data),
        "body_1_wrench": wrench_to_gz(msg.body_1_wrench),
        "body_2_wrench": wrench_to_gz(msg.body_2_wrench),
    }


def contact_to_ros(m: GzDict) -> Any:
    return make_msg(
        "ros_gz_interfaces/msg/Contact",
        collision1=entity_to_ros(m.get("collision1")),
        collision2=entity_to_ros(m.get("collision2")),
        positions=[vector3_to_ros(p) for p in m.get("position") or []],
        normals=[vector3_to_ros(n) for n in m.get("normal") or []],
        depths=np.asarray(m.get("depth") if m.get("depth") is not None else [], dtype=np.float64),
        wrenches=[joint_wrench_to_ros(w) for w in m.get("wrench") or []],
    )


def contact_to_gz(msg: Any) -> GzDict:
    return {
        "collision1": entity_to_gz(msg.collision1),
        # ros_gz_bridge (jazzy) fills collision2 from collision1 in this direction; kept as it does
        "collision2": entity_to_gz(msg.collision1),
        "position": [vector3_to_gz(p) for p in msg.positions],
        "normal": [vector3_to_gz(n) for n in msg.normals],
        "depth": [float(d) for d in msg.depths],
        "wrench": [joint_wrench_to_gz(w) for w in msg.wrenches],
    }


def contacts_to_ros(m: GzDict) -> Any:
    return make_msg(
        "ros_gz_interfaces/msg/Contacts",
        header=header_to_ros(m.get("header")),
        contacts=[contact_to_ros(c) for c in m.get("contact") or []],
    )


def contacts_to_gz(msg: Any) -> GzDict:
    return {"header": header_to_gz(msg.header), "contact": [contact_to_gz(c) for c in msg.contacts]}


def dataframe_to_ros(m: GzDict) -> Any:
    h = m.get("header")
    rssi = 0.0
    text = gz.header_value(h, "rssi", "")
    if text:
        try:
            rssi = float(text)
        except ValueError:
            raise MessageError(f"Dataframe rssi {text!r} is not a number") from None
    data = m.get("data") or b""
    return make_msg(
        "ros_gz_interfaces/msg/Dataframe",
        header=header_to_ros(h),
        src_address=str(m.get("src_address", "")),
        dst_address=str(m.get("dst_address", "")),
        data=np.frombuffer(bytes(data), dtype=np.uint8).copy(),
        rssi=rssi,
    )


def dataframe_to_gz(msg: Any) -> GzDict:
    header = header_to_gz(msg.header)
    # std::to_string(double): fixed notation, six decimals
    header["data"].append({"key": "rssi", "value": [f"{float(msg.rssi):f}"]})
    return {
        "header": header,
        "src_address": msg.src_address,
        "dst_address": msg.dst_address,
        "data": bytes(np.asarray(msg.data, dtype=np.uint8)),
    }


def float_v_to_ros(m: GzDict) -> Any:
    values = m.get("data")
    return make_msg(
        "ros_gz_interfaces/msg/Float32Array", data=np.asarray(values if values is not None else [], dtype=np.float32)
    )


def float_v_to_gz(msg: Any) -> GzDict:
    return {"data": [float(v) for v in msg.data]}


def string_v_to_ros(m: GzDict) -> Any:
    data = [str(s) for s in m.get("data") or []]
    return make_msg("ros_gz_interfaces/msg/StringVec", header=header_to_ros(m.get("header")), data=data)


def string_v_to_gz(msg: Any) -> GzDict:
    return {"header": header_to_gz(msg.header), "data": list(msg.data)}


def _parameters(param: GzDict, prefix: str = "") -> list[Any]:
    """A gz Param's params, then its children's as `child_<i>/<name>`, as ros_gz_bridge flattens them."""
    out = [
        make_msg("rcl_interfaces/msg/Parameter", name=prefix + str(name), value=any_to_parameter_value(value or {}))
        for name, value in (param.get("params") or {}).items()
    ]
    for i, child in enumerate(param.get("children") or []):
        out.extend(_parameters(child, f"{prefix}child_{i}/"))
    return out


def param_to_ros(m: GzDict) -> Any:
    return make_msg("ros_gz_interfaces/msg/ParamVec", header=header_to_ros(m.get("header")), params=_parameters(m))


def param_to_gz(msg: Any) -> GzDict:
    return {
        "header": header_to_gz(msg.header),
        "params": {p.name: parameter_value_to_any(p.value) for p in msg.params},
    }


def param_v_to_ros(m: GzDict) -> Any:
    params = []
    for i, param in enumerate(m.get("param") or []):
        params.extend(_parameters(param, f"param_{i}/"))
    return make_msg("ros_gz_interfaces/msg/ParamVec", header=header_to_ros(m.get("header")), params=params)


def param_v_to_gz(msg: Any) -> GzDict:
    # ros_gz_bridge puts every parameter in the vector's first entry (no round trip of the names)
    return {"header": header_to_gz(msg.header), "param": [param_to_gz(msg)]}
