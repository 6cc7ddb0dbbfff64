"""Messages as ordered dicts, YAML and CSV, with rosidl_runtime_py's truncation and abbreviation rules."""

from __future__ import annotations

import array
import sys
from collections import OrderedDict
from typing import Any

import numpy
import yaml

from diffctl.interfaces import definition

_SEQUENCES = (list, tuple, array.array, numpy.ndarray)
_representer_added = False


def _value_type_name(t: Any) -> str:
    if isinstance(t, definition.BasicType):
        return t.typename
    if isinstance(t, definition.AbstractString):
        return "string"
    if isinstance(t, definition.AbstractWString):
        return "wstring"
    if isinstance(t, definition.NamedType):
        return t.name
    if isinstance(t, definition.NamespacedType):
        return "/".join(t.namespaced_name())
    return "unknown"


def _abbreviated(value: Any, field_type: Any) -> str:
    name = _value_type_name(field_type.value_type)
    if isinstance(field_type, definition.Array):
        return f"<array type: {name}[{field_type.size}]>"
    if isinstance(field_type, definition.BoundedSequence):
        return f"<sequence type: {name}[{field_type.maximum_size}], length: {len(value)}>"
    if isinstance(field_type, definition.UnboundedSequence):
        return f"<sequence type: {name}, length: {len(value)}>"
    return "unknown"


def _slot_types(msg: Any) -> Any:
    return zip(msg.get_fields_and_field_types().keys(), msg.SLOT_TYPES, strict=False)


def get_message_slot_types(msg: Any) -> OrderedDict:
    """Field name → rosidl_parser.definition type of a message (class or instance)."""
    return OrderedDict(_slot_types(msg))


def _convert(value: Any, field_type: Any = None, truncate_length: int | None = None, no_arr: bool = False,
             no_str: bool = False) -> Any:
    if isinstance(value, bytes):
        shown = value if truncate_length is None or len(value) <= truncate_length else value[:truncate_length]
        text = "".join(chr(c) for c in shown)
        return text + "..." if shown is not value else text
    if isinstance(value, str):
        if no_str:
            return f"<string length: <{len(value)}>>"
        if truncate_length is not None and len(value) > truncate_length:
            return value[:truncate_length] + "..."
        return value
    if isinstance(value, _SEQUENCES):
        make = tuple if isinstance(value, tuple) else list
        if no_arr and field_type is not None:
            return _abbreviated(value, field_type)
        if truncate_length is not None and len(value) > truncate_length:
            items = [_convert(v, None, truncate_length, no_arr, no_str) for v in value[:truncate_length]]
            return make([*items, "..."])
        return make([_convert(v, None, truncate_length, no_arr, no_str) for v in value])
    if isinstance(value, dict):
        # rosidl_runtime_py builds a plain dict for both (its OrderedDict branch is unreachable)
        return {_convert(k): _convert(v, None, truncate_length, no_arr, no_str) for k, v in value.items()}
    if isinstance(value, numpy.number):
        return value.item()
    if isinstance(value, (bool, float, int)):
        return value
    return message_to_ordereddict(value, truncate_length=truncate_length, no_arr=no_arr, no_str=no_str)


def message_to_ordereddict(msg: Any, *, truncate_length: int | None = None, no_arr: bool = False,
                           no_str: bool = False) -> OrderedDict:
    """Field name → value, nested messages as OrderedDicts, collections as lists, bytes as strings."""
    out: OrderedDict = OrderedDict()
    for name, field_type in _slot_types(msg):
        out[name] = _convert(getattr(msg, name, None), field_type, truncate_length, no_arr, no_str)
    return out


def _represent_ordereddict(dumper: yaml.Dumper, data: OrderedDict) -> yaml.nodes.MappingNode:
    items = [(dumper.represent_data(k), dumper.represent_data(v)) for k, v in data.items()]
    return yaml.nodes.MappingNode("tag:yaml.org,2002:map", items)


def message_to_yaml(msg: Any, *, truncate_length: int | None = None, no_arr: bool = False, no_str: bool = False,
                    flow_style: bool = False) -> str:
    """The message as YAML, fields in their order (what `ros2 topic echo` prints)."""
    global _representer_added
    if not _representer_added:
        # rosidl_runtime_py registers it on PyYAML's default Dumper too: output keeps the field order
        yaml.add_representer(OrderedDict, _represent_ordereddict)
        _representer_added = True
    return yaml.dump(message_to_ordereddict(msg, truncate_length=truncate_length, no_arr=no_arr, no_str=no_str),
                     allow_unicode=True, width=sys.maxsize, default_flow_style=flow_style)


def message_to_csv(msg: Any, *, truncate_length: int | None = None, no_arr: bool = False,
                   no_str: bool = False) -> str:
    """The message's values, depth first, separated by commas (`ros2 topic echo --csv`)."""

    def text(val: Any, field_type: Any = None) -> str:
        if isinstance(val, _SEQUENCES):
            if no_arr and field_type is not None:
                return _abbreviated(val, field_type)
            # A comma goes before an item only when something came before it: empty items leave none.
            out = ""
            for i, v in enumerate(val):
                if out:
                    out += ","
                if truncate_length is not None and i >= truncate_length:
                    out += "..."
                    break
                out += text(v)
            return out
        if isinstance(val, (bool, bytes, float, int, str, numpy.number)):
            if no_str and isinstance(val, str):
                val = f"<string length: <{len(val)}>>"
            elif isinstance(val, (bytes, str)) and truncate_length is not None and len(val) > truncate_length:
                val = val[:truncate_length] + (b"..." if isinstance(val, bytes) else "...")
            return str(val)
        return message_to_csv(val, truncate_length=truncate_length, no_arr=no_arr, no_str=no_str)

    result = ""
    for name, field_type in _slot_types(msg):
        if result:
            result += ","
        result += text(getattr(msg, name), field_type)
    return result
