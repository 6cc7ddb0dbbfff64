"""Message, service and action classes as rosidl generates them for Python, without a ROS build.

The contract other client modules code against:

    get_interface("geometry_msgs/msg/Twist") -> class       # also pkg/srv/T, pkg/action/T and their parts
    serialize(msg) -> bytes                                  # CDR with its 4-byte header, as on the wire
    deserialize(data, cls) -> msg
    type_name(cls_or_msg) -> "pkg/msg/T"                     # "pkg/srv/T_Request", "pkg/action/T_Goal", …
    type_hash(cls_or_msg) -> "RIHS01_<64 hex>"

Importing this package installs the import hook (`hook.py`), so `from geometry_msgs.msg import Twist`
works after it even where the .pth file is not processed. Everything heavier is imported on first use.
"""

from __future__ import annotations

from diffctl.interfaces import hook as _hook  # noqa: F401  (installs the finder)

# No module-level imports beyond the hook: this package is imported at every interpreter's start (the .pth).

_encoders: dict[type, object] = {}
_decoders: dict[type, object] = {}


def get_interface(name: str) -> type:
    """The class of an interface or one of its parts; `pkg/T` means `pkg/msg/T`. ImportError if unknown."""
    from diffctl.interfaces import classes

    parts = [p for p in name.strip().split("/") if p]
    if len(parts) == 2:
        parts = [parts[0], "msg", parts[1]]
    if len(parts) != 3 or parts[1] not in ("msg", "srv", "action"):
        raise ValueError(f"malformed interface name {name!r}: expected pkg/msg/Type, pkg/srv/Type or pkg/action/Type")
    return classes.interface_class("/".join(parts))


def type_name(cls_or_msg: object) -> str:
    """`pkg/msg/T` of a class or message built here (service and action parts keep their suffix)."""
    from diffctl.interfaces.classes import NAMES

    cls = cls_or_msg if isinstance(cls_or_msg, type) else type(cls_or_msg)
    try:
        return NAMES[cls]
    except KeyError:
        raise TypeError(f"{cls!r} is not an interface class of diffctl.interfaces") from None


def type_hash(cls_or_msg: object) -> str:
    """The RIHS01 type hash rosidl computes (REP-2016), as on the rmw_zenoh wire."""
    from diffctl.interfaces import types

    return types.type_hash(type_name(cls_or_msg))


def serialize(msg: object) -> bytes:
    """The message as a little-endian CDR sample with its encapsulation header."""
    enc = _encoders.get(msg.__class__)
    if enc is None:
        from diffctl.interfaces import codec

        enc = _encoders[msg.__class__] = codec.encoder(msg.__class__)
    return enc(msg)


def deserialize(data: bytes | bytearray | memoryview, cls: type) -> object:
    """A message of `cls` from a CDR sample (header included); MessageError on malformed data."""
    dec = _decoders.get(cls)
    if dec is None:
        from diffctl.interfaces import codec

        dec = _decoders[cls] = codec.decoder(cls)
    return dec(data)


__all__ = ["deserialize", "get_interface", "serialize", "type_hash", "type_name"]
