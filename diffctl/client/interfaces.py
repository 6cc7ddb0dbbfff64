"""Message classes the client library itself uses, looked up once through diffctl.interfaces."""

from __future__ import annotations

import functools
from typing import Any


@functools.cache
def cls(name: str) -> Any:
    """The generated class of `pkg/msg/Type` (or a service type)."""
    from diffctl import interfaces as messages

    return messages.get_interface(name)


def type_name(msg_type: Any) -> str:
    from diffctl import interfaces as messages

    return messages.type_name(msg_type)


def serialize(msg: Any) -> bytes:
    from diffctl import interfaces as messages

    return messages.serialize(msg)


def deserialize(data: bytes, msg_type: Any) -> Any:
    from diffctl import interfaces as messages

    return messages.deserialize(data, msg_type)


def check_message_type(msg_type: Any) -> str:
    """The ROS name of a message class; TypeError for anything else (a service or a plain object)."""
    try:
        return type_name(msg_type)
    except Exception:
        raise TypeError(f"{msg_type!r} is not a ROS message class (import it as `from pkg.msg import Type`)") from None
