"""vision_msgs detections as ros_gz_bridge converts them (ros_gz_bridge/src/convert/vision_msgs.cpp, jazzy):
Detection2D ↔ AnnotatedAxisAligned2DBox, Detection3D ↔ AnnotatedOriented3DBox and their arrays ↔ `_V`.

gz layouts: AnnotatedAxisAligned2DBox `{"header", "box": {"min_corner": V2, "max_corner": V2}, "label": n}`;
AnnotatedOriented3DBox `{"header", "box": {"center": V3, "boxsize": V3, "orientation": Q}, "label": n}`;
their `_V` `{"header", "annotated_box": [box]}` (V2 = {"x", "y"}).

As upstream: only the first result's class_id travels to gz (read as C++ std::stoi reads it, into gz's uint32
label); from gz one result comes back, class_id the label's decimal text and score 1.0; a 2D box's theta and
the detection's id are not carried.
"""

from __future__ import annotations

import re
from typing import Any

from diffctl.bridge.conversions import (
    GzDict,
    float_field,
    header_to_gz,
    header_to_ros,
    quaternion_to_gz,
    quaternion_to_ros,
    vector3_to_gz,
)
from diffctl.errors import MessageError
from diffctl.interfaces import types

# std::stoi: leading white space, an optional sign, then digits; anything after them is ignored
_STOI = re.compile(r"\s*([+-]?\d+)")
_INT32 = (-(2**31), 2**31 - 1)


def class_id_to_label(class_id: str) -> int:
    """gz's uint32 label from a hypothesis' class_id, as ros_gz_bridge's `set_label(std::stoi(id))`."""
    m = _STOI.match(class_id)
    if m is None:
        raise MessageError(f"results[0].hypothesis.class_id {class_id!r} is not an integer (gz labels are numbers)")
    value = int(m.group(1))
    if not _INT32[0] <= value <= _INT32[1]:
        raise MessageError(f"results[0].hypothesis.class_id {class_id!r} is out of int range")
    return value & 0xFFFFFFFF  # a negative int set on protobuf's uint32 wraps


def _label_of(msg: Any) -> dict[str, int]:
    return {"label": class_id_to_label(msg.results[0].hypothesis.class_id)} if len(msg.results) else {}


def _results(m: GzDict) -> list[Any]:
    hyp = types.new("vision_msgs/msg/ObjectHypothesisWithPose")
    hyp.hypothesis.class_id = str(int(m.get("label", 0)))
    hyp.hypothesis.score = 1.0
    return [hyp]


def detection2d_to_ros(m: GzDict) -> Any:
    box = m.get("box") or {}
    lo, hi = box.get("min_corner"), box.get("max_corner")
    msg = types.new("vision_msgs/msg/Detection2D")
    msg.header = header_to_ros(m.get("header"))
    msg.results = _results(m)
    msg.bbox.center.position.x = (float_field(lo, "x") + float_field(hi, "x")) / 2
    msg.bbox.center.position.y = (float_field(lo, "y") + float_field(hi, "y")) / 2
    msg.bbox.size_x = float_field(hi, "x") - float_field(lo, "x")
    msg.bbox.size_y = float_field(hi, "y") - float_field(lo, "y")
    return msg


def detection2d_to_gz(msg: Any) -> GzDict:
    c, sx, sy = msg.bbox.center.position, float(msg.bbox.size_x), float(msg.bbox.size_y)
    return {
        "header": header_to_gz(msg.header),
        **_label_of(msg),
        "box": {
            "min_corner": {"x": c.x - sx / 2, "y": c.y - sy / 2},
            "max_corner": {"x": c.x + sx / 2, "y": c.y + sy / 2},
        },
    }


def detection3d_to_ros(m: GzDict) -> Any:
    box = m.get("box") or {}
    center, size = box.get("center"), box.get("boxsize")
    msg = types.new("vision_msgs/msg/Detection3D")
    msg.header = header_to_ros(m.get("header"))
    msg.results = _results(m)
    p = msg.bbox.center.position
    p.x, p.y, p.z = (float_field(center, k) for k in "xyz")
    msg.bbox.size.x, msg.bbox.size.y, msg.bbox.size.z = (float_field(size, k) for k in "xyz")
    msg.bbox.center.orientation = quaternion_to_ros(box.get("orientation"))
    return msg


def detection3d_to_gz(msg: Any) -> GzDict:
    p = msg.bbox.center.position
    return {
        "header": header_to_gz(msg.header),
        **_label_of(msg),
        "box": {
            "center": {"x": float(p.x), "y": float(p.y), "z": float(p.z)},
            "boxsize": vector3_to_gz(msg.bbox.size),
            "orientation": quaternion_to_gz(msg.bbox.center.orientation),
        },
    }


def detection2d_array_to_ros(m: GzDict) -> Any:
    msg = types.new("vision_msgs/msg/Detection2DArray")
    msg.header = header_to_ros(m.get("header"))
    msg.detections = [detection2d_to_ros(b) for b in m.get("annotated_box") or []]
    return msg


def detection2d_array_to_gz(msg: Any) -> GzDict:
    return {"header": header_to_gz(msg.header), "annotated_box": [detection2d_to_gz(d) for d in msg.detections]}


def detection3d_array_to_ros(m: GzDict) -> Any:
    msg = types.new("vision_msgs/msg/Detection3DArray")
    msg.header = header_to_ros(m.get("header"))
    msg.detections = [detection3d_to_ros(b) for b in m.get("annotated_box") or []]
    return msg


def detection3d_array_to_gz(msg: Any) -> GzDict:
    return {"header": header_to_gz(msg.header), "annotated_box": [detection3d_to_gz(d) for d in msg.detections]}
