"""rcl_interfaces parameter messages ↔ Python values and descriptors (as dicts for `types.new`)."""

from __future__ import annotations

from typing import Any

from diffctl.bus.parameters import TYPE_CODES, TYPE_NAMES, ParameterDescriptor, type_of

_FIELD = {
    "bool": "bool_value", "integer": "integer_value", "double": "double_value", "string": "string_value",
    "byte_array": "byte_array_value", "bool_array": "bool_array_value", "integer_array": "integer_array_value",
    "double_array": "double_array_value", "string_array": "string_array_value",
}


def to_value(value: Any) -> dict[str, Any]:
    """A Python value as rcl_interfaces/msg/ParameterValue fields (ValueError if no ROS type holds it)."""
    kind = type_of(value)
    if kind == "not_set":
        return {"type": 0}
    v: Any = value
    if kind == "double_array":
        v = [float(x) for x in value]
    elif kind == "byte_array":
        v = list(bytes(value))
    elif kind.endswith("_array"):
        v = list(value)
    return {"type": TYPE_CODES[kind], _FIELD[kind]: v}


def from_value(msg: Any) -> Any:
    """An rcl_interfaces/msg/ParameterValue message as a Python value (None for NOT_SET or an unknown type)."""
    kind = TYPE_NAMES.get(int(msg.type), "not_set")
    if kind == "not_set":
        return None
    raw = getattr(msg, _FIELD[kind])
    if kind == "byte_array":
        # rclpy's byte[] fields hold one-byte bytes objects (b'\xff'); diffctl's decoder gives ints
        return bytes(x[0] if isinstance(x, (bytes, bytearray)) else int(x) for x in raw)
    if kind.endswith("_array"):
        cast = {"bool_array": bool, "integer_array": int, "double_array": float, "string_array": str}[kind]
        return [cast(x) for x in raw]
    return {"bool": bool, "integer": int, "double": float, "string": str}[kind](raw)


def to_descriptor(name: str, desc: ParameterDescriptor) -> dict[str, Any]:
    """rcl_interfaces/msg/ParameterDescriptor fields for a parameter."""
    out: dict[str, Any] = {
        "name": name, "type": TYPE_CODES.get(desc.type or "not_set", 0), "description": desc.description,
        "additional_constraints": desc.additional_constraints, "read_only": desc.read_only,
        "dynamic_typing": desc.dynamic_typing,
    }
    if desc.floating_point_range is not None:
        lo, hi, step = desc.floating_point_range
        out["floating_point_range"] = [{"from_value": float(lo), "to_value": float(hi), "step": float(step)}]
    if desc.integer_range is not None:
        lo, hi, step = desc.integer_range
        out["integer_range"] = [{"from_value": int(lo), "to_value": int(hi), "step": int(step)}]
    return out


def from_descriptor(msg: Any) -> ParameterDescriptor:
    fr = msg.floating_point_range
    ir = msg.integer_range
    return ParameterDescriptor(
        type=TYPE_NAMES.get(int(msg.type), "not_set"), description=str(msg.description),
        read_only=bool(msg.read_only), dynamic_typing=bool(msg.dynamic_typing),
        additional_constraints=str(msg.additional_constraints),
        floating_point_range=(float(fr[0].from_value), float(fr[0].to_value), float(fr[0].step)) if fr else None,
        integer_range=(int(ir[0].from_value), int(ir[0].to_value), int(ir[0].step)) if ir else None,
    )
