"""Compiled CDR codecs for the generated classes: the bus's code generator (`diffctl.interfaces.cdr`), reading
fields from the classes' slots and building instances without their constructor, as rclpy's C conversion
does (fields set directly, `_check_fields` as the class's module has it).

A message the compiled encoder cannot take (a field of the wrong type: field checks are off by default) is
converted once more the way rosidl's C conversion reads it, and encoded from that: integers wrap to their
width, a bool field is true only for True, numeric sequences go through `array.array` (with its overflow and
type errors), strings must be str ("bad argument type for built-in operation"), nested messages are read by
their public field names (AttributeError on what has none). Where rosidl reads undefined memory (an int or
str in a float field, an int in a byte field) diffctl converts the value (1 → 1.0) or raises TypeError.
"""

from __future__ import annotations

import array
from collections.abc import Callable
from typing import Any

import numpy
from rosbags.typesys.base import Nodetype

from diffctl.errors import MessageError
from diffctl.interfaces import cdr, classes, types

_TYPECODE = {"int8": "b", "uint8": "B", "int16": "h", "uint16": "H", "int32": "i", "uint32": "I", "int64": "q",
             "uint64": "Q", "float32": "f", "float64": "d"}
_BITS = {"int8": 8, "uint8": 8, "int16": 16, "uint16": 16, "int32": 32, "uint32": 32, "int64": 64, "uint64": 64}
_EMPTY = "structure_needs_at_least_one_member"


def _typename(cls: type) -> str:
    name = classes.NAMES.get(cls)
    if name is None or name.split("/")[-1] != cls.__name__:
        raise TypeError(f"{cls!r} is not a message class of diffctl.interfaces")
    if "_CREATE_ROS_MESSAGE" not in vars(type(cls)):
        raise TypeError(f"{name} is a service or action, not a message: use its Request/Response/Goal/… classes")
    return name


def encoder(cls: type) -> Callable[[Any], bytes]:
    name = _typename(cls)
    ts = types.store_described(name)
    fast = cdr.compile_encoder(ts, name, rosidl=True)

    def encode(msg: Any) -> bytes:
        try:
            return fast(msg)
        except (TypeError, ValueError, AttributeError, OverflowError, cdr.struct.error):
            return fast(_as_c_reads(msg, name, ts))

    return encode


def decoder(cls: type) -> Callable[[bytes | bytearray | memoryview], Any]:
    name = _typename(cls)
    return cdr.compile_decoder(types.store_described(name), name, MessageError, classes=classes.interface_class)


def _wrap(value: Any, base: str) -> int:
    if isinstance(value, float) or not isinstance(value, int):
        raise TypeError(f"'{type(value).__name__}' object cannot be interpreted as an integer")
    bits = _BITS[base]
    if not -(2 ** (bits if bits == 64 and base.startswith("u") else 63)) <= value < 2**64:
        raise OverflowError(f"Python int too large to convert to C {'unsigned ' if base[0] == 'u' else ''}long")
    value &= (1 << bits) - 1
    return value - (1 << bits) if not base.startswith("u") and value >= 1 << (bits - 1) else value


def _scalar(value: Any, base: str) -> Any:
    if base in ("string", "wstring", "char", "wchar"):
        if not isinstance(value, str):
            raise TypeError("bad argument type for built-in operation")
        return value
    if base == "bool":
        return value is True
    if base in ("float32", "float64"):
        if isinstance(value, (int, float, numpy.number)) and not isinstance(value, bool):
            return float(value)
        raise TypeError(f"must be real number, not {type(value).__name__}")
    if base == "byte":
        if isinstance(value, (bytes, bytearray)) and len(value) == 1:
            return bytes(value)
        return bytes([_wrap(value, "uint8") & 0xFF])
    return _wrap(value, base)


def _value(value: Any, desc: tuple, ts: Any) -> Any:
    kind, spec = desc
    if kind == Nodetype.BASE:
        return _scalar(value, spec[0])
    if kind == Nodetype.NAME:
        return _as_c_reads(value, spec, ts)
    sub, _ = spec
    if sub[0] == Nodetype.BASE and sub[1][0] in _TYPECODE:
        if isinstance(value, numpy.ndarray):
            return value
        code = _TYPECODE[sub[1][0]]
        return value if isinstance(value, array.array) and value.typecode == code else array.array(code, value)
    return [_value(v, sub, ts) for v in value]


def _as_c_reads(msg: Any, typename: str, ts: Any) -> Any:
    """A copy of `msg` with every field as rosidl's C conversion would read it (public field names)."""
    cls = classes.interface_class(typename)
    out = object.__new__(cls)
    out._check_fields = getattr(msg, "_check_fields", False)
    for name, desc in ts.fielddefs[typename][1]:
        if name != _EMPTY:
            setattr(out, "_" + name, _value(getattr(msg, name), desc, ts))
    return out
