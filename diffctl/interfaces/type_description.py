"""REP-2016 type descriptions: the structure a RIHS01 hash is computed from.

`describe()` builds type_description_interfaces/msg/TypeDescription as plain data from the typestore's field
definitions, exactly the form rosidl writes into `share/<pkg>/msg/<Type>.json`, so the same function serves
every node's `~/get_type_description` and the Jazzy oracle test. `hash_of()` hashes it the way REP-2016
says (JSON of the description without default values, sha256).
"""

from __future__ import annotations

import hashlib
import json
from typing import Any

from rosbags.typesys.base import Nodetype

from diffctl.interfaces import types

# type_description_interfaces/msg/FieldType
FIELD_TYPE_IDS = {
    "nested": 1, "int8": 2, "uint8": 3, "int16": 4, "uint16": 5, "int32": 6, "uint32": 7, "int64": 8,
    "uint64": 9, "float32": 10, "float64": 11, "longdouble": 12, "char": 13, "wchar": 14, "bool": 15,
    "byte": 16, "string": 17, "wstring": 18, "bounded_string": 21, "bounded_wstring": 22,
}
ARRAY_OFFSET, BOUNDED_SEQUENCE_OFFSET, UNBOUNDED_SEQUENCE_OFFSET = 48, 96, 144
SERVICE_TYPE = "type_description_interfaces/srv/GetTypeDescription"


def _field_type(desc: tuple) -> dict[str, Any]:
    offset = capacity = string_capacity = 0
    kind, spec = desc
    if kind == Nodetype.ARRAY:
        offset, (kind, spec), capacity = ARRAY_OFFSET, spec[0], spec[1]
    elif kind == Nodetype.SEQUENCE:
        bound = spec[1]
        offset = BOUNDED_SEQUENCE_OFFSET if bound else UNBOUNDED_SEQUENCE_OFFSET
        (kind, spec), capacity = spec[0], bound
    nested = ""
    if kind == Nodetype.NAME:
        tid, nested = FIELD_TYPE_IDS["nested"], spec
    else:
        base, bound = spec
        if base in ("string", "wstring") and bound:
            tid, string_capacity = FIELD_TYPE_IDS[f"bounded_{base}"], bound
        else:
            tid = FIELD_TYPE_IDS[base]
    return {"type_id": offset + tid, "capacity": capacity, "string_capacity": string_capacity,
            "nested_type_name": nested}


def individual(typename: str) -> dict[str, Any]:
    """IndividualTypeDescription of one type (an empty message gets rosidl's placeholder member)."""
    fields = types.store_described(typename).fielddefs[typename][1] or [
        ("structure_needs_at_least_one_member", (Nodetype.BASE, ("uint8", 0)))
    ]
    return {"type_name": typename,
            "fields": [{"name": n, "type": _field_type(d), "default_value": ""} for n, d in fields]}


def describe(typename: str) -> dict[str, Any]:
    """TypeDescription: the type and every type it references, those sorted by name."""
    seen: dict[str, dict[str, Any]] = {}
    todo = [typename]
    while todo:
        t = todo.pop()
        if t in seen:
            continue
        seen[t] = individual(t)
        todo += [f["type"]["nested_type_name"] for f in seen[t]["fields"] if f["type"]["nested_type_name"]]
    return {"type_description": seen[typename],
            "referenced_type_descriptions": [seen[k] for k in sorted(seen) if k != typename]}


def hash_of(description: dict[str, Any]) -> str:
    """RIHS01 of a TypeDescription: sha256 of its JSON with default values left out (REP-2016)."""
    def strip(ind: dict[str, Any]) -> dict[str, Any]:
        return {"type_name": ind["type_name"],
                "fields": [{"name": f["name"], "type": f["type"]} for f in ind["fields"]]}

    dct = {"type_description": strip(description["type_description"]),
           "referenced_type_descriptions": [strip(r) for r in description["referenced_type_descriptions"]]}
    return "RIHS01_" + hashlib.sha256(json.dumps(dct).encode()).hexdigest()


_BASE_OF_ID = {v: k for k, v in FIELD_TYPE_IDS.items()}
_SCHEMA_SEPARATOR = "=" * 80


def _msg_field_type(ft: dict[str, Any]) -> str:
    """A FieldType as .msg text: `float64[3]`, `string<=10`, `geometry_msgs/Point[]`, `int32[<=5]`."""
    tid, suffix = int(ft["type_id"]), ""
    if tid > UNBOUNDED_SEQUENCE_OFFSET:
        tid, suffix = tid - UNBOUNDED_SEQUENCE_OFFSET, "[]"
    elif tid > BOUNDED_SEQUENCE_OFFSET:
        tid, suffix = tid - BOUNDED_SEQUENCE_OFFSET, f"[<={ft['capacity']}]"
    elif tid > ARRAY_OFFSET:
        tid, suffix = tid - ARRAY_OFFSET, f"[{ft['capacity']}]"
    base = _BASE_OF_ID.get(tid)
    if base is None:
        raise ValueError(f"unknown field type id {ft['type_id']}")
    if base == "nested":
        base = _msg_name(str(ft["nested_type_name"]))
    elif base.startswith("bounded_"):
        base = f"{base.removeprefix('bounded_')}<={ft['string_capacity']}"
    return base + suffix


def _msg_name(typename: str) -> str:
    """A type's name as .msg text spells it: `pkg/msg/T` → `pkg/T`; a service's or action's part
    (`pkg/srv/T_Request`, a `<srv>_Event`'s fields) keeps its full name, as rosbag2 writes it."""
    pkg, sep, name = typename.partition("/msg/")
    return f"{pkg}/{name}" if sep else typename


def ros2msg_text(description: dict[str, Any]) -> str:
    """A TypeDescription (as plain data) as rosbag2's concatenated .msg text: the type, then each type it
    references after a line of `=` and `MSG: pkg/Type` (what rosbags' `get_types_from_msg` reads)."""

    def body(ind: dict[str, Any]) -> str:
        fields = [f for f in ind["fields"] if f["name"] != "structure_needs_at_least_one_member"]
        return "\n".join(f"{_msg_field_type(f['type'])} {f['name']}" for f in fields)

    parts = [body(description["type_description"])]
    for ref in description["referenced_type_descriptions"]:
        parts.append(f"{_SCHEMA_SEPARATOR}\nMSG: {_msg_name(str(ref['type_name']))}\n{body(ref)}")
    return "\n".join(parts) + "\n"
