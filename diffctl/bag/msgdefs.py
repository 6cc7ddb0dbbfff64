"""Message definitions inside bags: `ros2msg` schema text for the types diffctl knows, and types learnt
from a bag's schemas (so a bag of a type diffctl has never heard of still plays and decodes).

The text is rosbag2's concatenated form: the root definition, then each dependency after a line of 80
`=` and `MSG: pkg/Type` — what rosbags' typestore generates from the same field definitions that the
bus uses, so the schema and the CDR on the wire can never disagree.
"""

from __future__ import annotations

import threading

from rosbags.typesys import get_types_from_idl, get_types_from_msg
from rosbags.typesys.base import Nodetype

from diffctl.errors import ConfigError, MessageError
from diffctl.interfaces import types

_lock = threading.Lock()


def ros2msg(typename: str) -> str:
    """The `ros2msg` schema text of a known type."""
    t = types.check(typename)
    text, _ = types.store().generate_msgdef(t, ros_version=2)
    return text


def _referenced(defs: dict) -> set[str]:
    """The message types the fields of `defs` (rosbags field definitions) refer to."""
    out = set()
    for _consts, fields in defs.values():
        for _name, (kind, spec) in fields:
            if kind in (Nodetype.ARRAY, Nodetype.SEQUENCE):
                kind, spec = spec[0]
            if kind == Nodetype.NAME:
                out.add(spec)
    return out


def _service_parts_named_in_full(defs: dict) -> dict:
    """rosbags reads `MSG: pkg/srv/X_Request` (a `<srv>_Event`'s parts) as `pkg/srv/msg/X_Request`; such a
    type is `pkg/srv/X_Request` on the bus, so the names and every reference to them are put back."""
    renamed = {k: k.replace("/srv/msg/", "/srv/").replace("/action/msg/", "/action/") for k in defs}
    renamed = {k: v for k, v in renamed.items() if k != v}
    if not renamed:
        return defs

    def fix(desc: tuple) -> tuple:
        kind, spec = desc
        if kind in (Nodetype.ARRAY, Nodetype.SEQUENCE):
            return kind, (fix(spec[0]), *spec[1:])
        if kind == Nodetype.NAME:
            return kind, renamed.get(spec, spec)
        return desc

    return {renamed.get(name, name): (consts, [(fname, fix(desc)) for fname, desc in fields])
            for name, (consts, fields) in defs.items()}


def register_schema(typename: str, encoding: str, text: str, source: str) -> bool:
    """Make `typename` (and its dependencies) known from a bag schema; True if anything was added.

    Types diffctl already knows keep their own definition: the bus's hash must stay that of Jazzy.
    """
    if types.exists(typename):
        return False
    try:
        if encoding == "ros2msg":
            found = get_types_from_msg(text, typename)
        elif encoding == "ros2idl":
            found = get_types_from_idl(text)
        else:
            raise ConfigError(f"schema of {typename} has encoding {encoding!r}", source=source,
                              hint="ros2msg and ros2idl schemas are read")
    except ConfigError:
        raise
    except Exception as e:  # rosbags' parsers raise their own error types on bad text
        raise MessageError(f"cannot parse the {encoding} schema of {typename}: {e}", source=source) from None
    found = _service_parts_named_in_full(found)
    with _lock:
        store = types.store()
        new = {k: v for k, v in found.items() if not types.exists(k)}
        for known in _referenced(new) - new.keys():
            if types.exists(known):
                types.store_with(known)  # diffctl registers its own types on first use: the new ones refer to them
        if new:
            store.register(new)
    if not types.exists(typename):
        raise MessageError(f"the {encoding} schema of {typename} does not define {typename}", source=source)
    return bool(new)
