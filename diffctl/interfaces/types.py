"""Message and service types: rosbags' Jazzy typestore plus the ROS types it lacks, and dict ↔ message.

Project types (controller_manager_msgs, control_msgs, std_srvs, …) are defined from their .msg/.srv text
in `interfaces.py` and registered in the same store, so their RIHS01 hashes follow REP-2016 exactly as
rosidl computes them (services hash their request/response/event wrapper).
"""

from __future__ import annotations

import functools
import math
import threading
from collections.abc import Callable
from dataclasses import fields as dc_fields
from typing import Any

import numpy as np
from rosbags.typesys import Stores, get_typestore
from rosbags.typesys.base import Nodetype

from diffctl.errors import ConfigError, MessageError, suggest
from diffctl.interfaces import cdr, typedefs

_lock = threading.RLock()
_store = None
_registered: set[str] = set()
# Types whose definitions are in the store (its `fielddefs`, enough for their RIHS01 hash and keys) but whose
# classes were not generated yet: a node declares its parameter and manager services by hash at start-up and
# builds their classes only when a request comes, if ever (25 ms of every node's start for 13 services).
_described: set[str] = set()

_NUMPY = {
    "bool": np.bool_, "byte": np.uint8, "char": np.uint8, "int8": np.int8, "uint8": np.uint8,
    "int16": np.int16, "uint16": np.uint16, "int32": np.int32, "uint32": np.uint32,
    "int64": np.int64, "uint64": np.uint64, "float32": np.float32, "float64": np.float64,
}
_INT_RANGE = {
    "byte": (0, 255), "char": (0, 255), "int8": (-128, 127), "uint8": (0, 255),
    "int16": (-(2**15), 2**15 - 1), "uint16": (0, 2**16 - 1), "int32": (-(2**31), 2**31 - 1),
    "uint32": (0, 2**32 - 1), "int64": (-(2**63), 2**63 - 1), "uint64": (0, 2**64 - 1),
}


def store():
    """The process-wide typestore; types enter it on first use (`_ensure`)."""
    global _store
    if _store is None:
        with _lock:
            if _store is None:
                _store = get_typestore(Stores.EMPTY)
    return _store


def _ensure(typename: str):
    """The store, with `typename` and everything it references registered."""
    ts = store()
    if typename in _registered:
        return ts
    with _lock:
        defs = typedefs.definitions()
        missing = [n for n in typedefs.closure(defs, [typename]) if n not in _registered]
        if missing:
            # rosbags makes classes only for names a store has no definition of, and some of these the store
            # describes already: they are made in a store of their own and moved in, so that a thread reading
            # the store meanwhile (compiling another type's codec) never finds a name gone from it.
            scratch = get_typestore(Stores.EMPTY)
            scratch.register({n: defs[n] for n in missing})
            for n in missing:
                ts.types[n] = scratch.types[n]
                ts.fielddefs[n] = scratch.fielddefs[n]
                _described.discard(n)
            _registered.update(missing)
    return ts


def _ensure_described(typename: str):
    """The store, with the definitions of `typename` and what it references (no classes generated)."""
    ts = store()
    if typename in _registered or typename in _described:
        return ts
    with _lock:
        defs = typedefs.definitions()
        for n in typedefs.closure(defs, [typename]):
            if n not in _registered and n not in _described:
                ts.fielddefs[n] = tuple(defs[n][:2])  # what `register` stores, without the generated code
                _described.add(n)
    return ts


def store_with(typename: str):
    """The typestore with `typename` (and what it references) registered."""
    return _ensure(typename)


def store_described(typename: str):
    """The typestore with the definitions of `typename` and what it references (enough for hashes and the
    compiled codecs of classes built elsewhere, e.g. diffctl.interfaces'), no rosbags classes generated."""
    return _ensure_described(typename)


def _all_names() -> list[str]:
    return list(typedefs.definitions())


def normalize(typename: str) -> str:
    """`pkg/Type`, `pkg/msg/Type` or the DDS form `pkg::msg::dds_::Type_` → `pkg/msg/Type`."""
    t = typename.strip()
    if "::dds_::" in t:
        return from_dds_name(t)
    parts = [p for p in t.replace("::", "/").split("/") if p]
    if len(parts) == 2:
        parts = [parts[0], "msg", parts[1]]
    if len(parts) != 3:
        raise MessageError(
            f"malformed type name {typename!r}", hint="expected pkg/msg/Type, e.g. geometry_msgs/msg/Twist"
        )
    return "/".join(parts)


def known_types() -> list[str]:
    return sorted(_all_names())


def exists(typename: str) -> bool:
    """Whether `typename` is known, counting interface packages the client library's registry reads (a
    service's `<srv>_Event` is defined there only, so `topic echo` of `/<srv>/_service_event` needs it)."""
    try:
        t = normalize(typename)
        _with_package_of(t)
        return t in _ensure(t).types
    except (MessageError, ConfigError):
        return False


def _with_package_of(typename: str) -> None:
    """Types of interface packages beyond diffctl's own definitions (the user's workspace, install trees, the
    Jazzy texts shipped with the client library) are read by diffctl.interfaces' registry, which enters
    them in `typedefs.definitions()`: asked only for a name not defined yet."""
    if typename in typedefs.definitions():
        return
    from diffctl.interfaces import registry

    registry.package(typename.split("/")[0])


def check(typename: str) -> str:
    """The normalized name of a known type; MessageError with close matches otherwise."""
    t = normalize(typename)
    _with_package_of(t)
    ts = _ensure(t)
    if t not in ts.types:
        raise MessageError(f"unknown message type {typename!r}{suggest(t, _all_names())}")
    return t


def check_defined(typename: str) -> str:
    """As `check`, without generating the type's class: an endpoint needs only its definition and hash until a
    message object is encoded or decoded (a node's /rosout and /parameter_events publishers, raw endpoints)."""
    t = normalize(typename)
    _with_package_of(t)
    if t in typedefs.definitions():
        return t
    return check(typename)


def check_service(typename: str) -> str:
    t = normalize(typename.replace("/msg/", "/srv/")) if "/msg/" not in typename else normalize(typename)
    if t.count("/") == 2 and t.split("/")[1] == "msg":
        t = t.replace("/msg/", "/srv/", 1)
    _with_package_of(f"{t}_Request")
    if f"{t}_Request" not in typedefs.definitions():
        services = [k for k in _all_names() if k.endswith("_Request")]
        raise MessageError(f"unknown service type {typename!r}{suggest(t + '_Request', services)}")
    _ensure_described(t)  # classes on first use (request, response, their codecs)
    return t


_classes: dict[str, Any] = {}


def get_class(typename: str):
    """The message class of `typename` (any accepted spelling); looked up once per spelling, since hot paths
    (the bridge's conversions, robot_state_publisher's TF) build several messages per sample."""
    cls = _classes.get(typename)
    if cls is None:
        cls = _classes[typename] = store().types[check(typename)]
    return cls


@functools.cache
def type_hash(typename: str) -> str:
    """RIHS01 hash (REP-2016) of a message or service type."""
    _with_package_of(typename)
    with _lock:  # `_ensure` may swap a described type's definition for its registration meanwhile
        ts = _ensure_described(typename)
        try:
            return ts.hash_rihs01(typename)
        except KeyError:  # rosbags hashes no wstring field; REP-2016's description itself covers them
            from diffctl.interfaces import type_description

            return type_description.hash_of(type_description.describe(typename))


def dds_name(typename: str) -> str:
    """`geometry_msgs/msg/Twist` → `geometry_msgs::msg::dds_::Twist_` (rmw_zenoh key and token form)."""
    pkg, kind, name = typename.split("/")
    return f"{pkg}::{kind}::dds_::{name}_"


def from_dds_name(dds: str) -> str:
    """Inverse of `dds_name`."""
    pkg, kind, _, name = dds.split("::")
    return f"{pkg}/{kind}/{name[:-1] if name.endswith('_') else name}"


# Per-type compiled (de)serializers (cdr.py), built on first use; a type cdr.py cannot compile keeps rosbags'.
_encoders: dict[str, Callable[[Any], bytes]] = {}
_decoders: dict[str, Callable[[bytes | bytearray | memoryview], Any]] = {}


def encoder(typename: str) -> Callable[[Any], bytes]:
    """`encode(msg) -> bytes` (CDR with its 4-byte header) for one type, cached: the publishers' hot path."""
    enc = _encoders.get(typename)
    if enc is None:
        ts = _ensure(typename)
        try:
            enc = cdr.compile_encoder(ts, typename)
        except cdr.Unsupported:
            def enc(msg: Any, _ts: Any = ts) -> bytes:
                return bytes(_ts.serialize_cdr(msg, typename))
        _encoders[typename] = enc
    return enc


def decoder(typename: str) -> Callable[[bytes | bytearray | memoryview], Any]:
    """`decode(raw) -> msg` for one type, cached; malformed data raises MessageError naming the type."""
    dec = _decoders.get(typename)
    if dec is None:
        ts = _ensure(typename)
        try:
            # Raises MessageError itself: a wrapper's call would cost every sample a frame.
            dec = cdr.compile_decoder(ts, typename, MessageError)
        except cdr.Unsupported:
            def dec(raw: bytes | bytearray | memoryview, _ts: Any = ts) -> Any:
                try:
                    return _ts.deserialize_cdr(raw, typename)
                except Exception as e:  # truncated or foreign data raise assorted errors
                    raise MessageError(f"cannot decode {typename}: {type(e).__name__}: {e}") from None

        _decoders[typename] = dec
    return dec


def serialize(msg: Any, typename: str) -> bytes:
    enc = _encoders.get(typename)
    return (enc or encoder(typename))(msg)


def deserialize(raw: bytes | bytearray | memoryview, typename: str) -> Any:
    dec = _decoders.get(typename)
    return (dec or decoder(typename))(raw)


# ----------------------------------------------------------------------------- dict ↔ message


# Default values written in .msg files (rosbags keeps types, not defaults); ROS fills these when unset.
_MSG_DEFAULTS: dict[str, dict[str, Any]] = {"geometry_msgs/msg/Quaternion": {"w": 1.0}}


def _field_defs(typename: str) -> list[tuple[str, tuple]]:
    return _ensure(typename).fielddefs[typename][1]


def _default(desc: tuple) -> Any:
    kind, spec = desc
    if kind == Nodetype.BASE:
        base = spec[0]
        if base == "string" or base == "wstring":
            return ""
        if base == "bool":
            return False
        if base in ("float32", "float64"):
            return 0.0
        return 0
    if kind == Nodetype.NAME:
        return new(spec, {})
    sub, count = spec
    if kind == Nodetype.ARRAY:
        if sub[0] == Nodetype.BASE and sub[1][0] in _NUMPY:
            return np.zeros(count, dtype=_NUMPY[sub[1][0]])
        return [_default(sub) for _ in range(count)]
    if sub[0] == Nodetype.BASE and sub[1][0] in _NUMPY:
        return np.zeros(0, dtype=_NUMPY[sub[1][0]])
    return []


def _convert(value: Any, desc: tuple, path: str) -> Any:
    kind, spec = desc
    if kind == Nodetype.BASE:
        return _scalar(value, spec[0], path)
    if kind == Nodetype.NAME:
        if isinstance(value, dict):
            return new(spec, value, _path=path)
        if type(value).__name__ == spec.split("/")[-1] and hasattr(value, "__msgtype__"):
            return value
        raise MessageError(f"field '{path}' must be a mapping for {spec}, got {_show(value)}")
    sub, count = spec
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if not isinstance(value, (list, tuple)):
        raise MessageError(f"field '{path}' must be a list, got {_show(value)}")
    if kind == Nodetype.ARRAY and len(value) != count:
        raise MessageError(f"field '{path}' must have exactly {count} elements, got {len(value)}")
    if kind == Nodetype.SEQUENCE and count and len(value) > count:
        raise MessageError(f"field '{path}' takes at most {count} elements, got {len(value)}")
    items = [_convert(v, sub, f"{path}[{i}]") for i, v in enumerate(value)]
    if sub[0] == Nodetype.BASE and sub[1][0] in _NUMPY:
        return np.array(items, dtype=_NUMPY[sub[1][0]])
    return items


def _show(value: Any) -> str:
    return f"{type(value).__name__} {value!r}"


def _scalar(value: Any, base: str, path: str) -> Any:
    if base in ("string", "wstring"):
        if isinstance(value, str):
            return value
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            return str(value)
        raise MessageError(f"field '{path}' must be a string, got {_show(value)}")
    if base == "bool":
        if isinstance(value, bool):
            return value
        raise MessageError(f"field '{path}' must be true or false, got {_show(value)}")
    if base in ("float32", "float64"):
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            return float(value)
        raise MessageError(f"field '{path}' must be a number ({base}), got {_show(value)}")
    if isinstance(value, bool) or not isinstance(value, int):
        if isinstance(value, float) and math.isfinite(value) and value.is_integer():
            value = int(value)
        else:
            raise MessageError(f"field '{path}' must be an integer ({base}), got {_show(value)}")
    lo, hi = _INT_RANGE.get(base, (-(2**63), 2**64 - 1))
    if not lo <= value <= hi:
        raise MessageError(f"field '{path}' = {value} is out of range for {base} [{lo}, {hi}]")
    return value


def new(typename: str, values: dict[str, Any] | None = None, *, _path: str = "") -> Any:
    """A message of `typename` from a (nested) dict; missing fields take ROS defaults.

    Unknown fields and wrong value types raise MessageError naming the field and listing valid ones.
    """
    t = check(typename) if not _path else typename
    values = values or {}
    if not isinstance(values, dict):
        raise MessageError(f"{_path or t}: expected a mapping of fields, got {_show(values)}")
    defs = _field_defs(t)
    names = [n for n, _ in defs]
    for k in values:
        if k not in names:
            where = f"{_path}.{k}" if _path else str(k)
            raise MessageError(
                f"unknown field '{where}' in {t}{suggest(str(k), names)}; valid fields: {', '.join(names) or '(none)'}"
            )
    kwargs = {}
    msg_defaults = _MSG_DEFAULTS.get(t, {})
    for name, desc in defs:
        p = f"{_path}.{name}" if _path else name
        if name in values:
            kwargs[name] = _convert(values[name], desc, p)
        else:
            kwargs[name] = msg_defaults[name] if name in msg_defaults else _default(desc)
    return store().types[t](**kwargs)


def to_dict(msg: Any) -> Any:
    """A message as plain Python data (numpy arrays → lists), ready for YAML or JSON."""
    if hasattr(msg, "__dataclass_fields__"):
        typename = getattr(msg, "__msgtype__", None)
        if typename:
            # The type's fields only: rosbags' generated classes also carry the .msg constants as attributes.
            return {n: to_dict(getattr(msg, n)) for n, _ in _field_defs(typename)}
        return {f.name: to_dict(getattr(msg, f.name)) for f in dc_fields(msg) if f.name != "__msgtype__"}
    if isinstance(msg, np.ndarray):
        return msg.tolist()
    if isinstance(msg, (list, tuple)):
        return [to_dict(v) for v in msg]
    if isinstance(msg, np.generic):
        return msg.item()
    return msg


def request(service_type: str, values: dict[str, Any] | None = None) -> Any:
    return new(check_service(service_type) + "_Request", values)


def response(service_type: str, values: dict[str, Any] | None = None) -> Any:
    return new(check_service(service_type) + "_Response", values)


def time_msg(ns: int) -> Any:
    time_cls = get_class("builtin_interfaces/msg/Time")
    return time_cls(sec=int(ns // 1_000_000_000), nanosec=int(ns % 1_000_000_000))


def time_ns(t: Any) -> int:
    return int(t.sec) * 1_000_000_000 + int(t.nanosec)


def _field_type_text(desc: tuple) -> str:
    kind, spec = desc
    if kind == Nodetype.BASE:
        return spec[0] + (f"<={spec[1]}" if spec[1] else "")
    if kind == Nodetype.NAME:
        return spec
    sub, count = spec
    inner = _field_type_text(sub)
    if kind == Nodetype.ARRAY:
        return f"{inner}[{count}]"
    return f"{inner}[<={count}]" if count else f"{inner}[]"


def _msg_text(typename: str) -> str:
    consts, flds = _ensure(typename).fielddefs[typename]
    lines = [f"{t} {n}={v}" for n, t, v in consts]
    lines += [f"{_field_type_text(d)} {n}" for n, d in flds]
    return "\n".join(lines)


def definition(typename: str) -> str:
    """The .msg/.srv-like text of a type (for `diffctl interface show`)."""
    t = normalize(typename)
    _with_package_of(t)
    if "/srv/" not in t and t in _ensure(t).types:
        return _msg_text(t) + "\n"
    s = check_service(t)
    return f"{_msg_text(s + '_Request')}\n---\n{_msg_text(s + '_Response')}\n"
