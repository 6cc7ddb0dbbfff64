"""rclpy.serialization: CDR bytes (with the encapsulation header) of a message, and back."""

from __future__ import annotations

from typing import Any

from diffctl.client.interfaces import check_message_type, deserialize, serialize


def serialize_message(message: Any) -> bytes:
    check_message_type(type(message))
    return serialize(message)


def deserialize_message(serialized_message: bytes, message_type: Any) -> Any:
    check_message_type(message_type)
    return deserialize(bytes(serialized_message), message_type)
