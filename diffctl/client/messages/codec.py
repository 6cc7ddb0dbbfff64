"""Compiled CDR codecs for the generated classes: the bus's code generator (`diffctl.bus.cdr`), reading
fields from the classes' slots and building instances without their constructor, as rclpy's C conversion
does (fields set directly, `_check_fields` as the class's module has it)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from diffctl.bus import cdr, types
from diffctl.client.messages import classes
from diffctl.errors import MessageError


def _typename(cls: type) -> str:
    name = classes.NAMES.get(cls)
    if name is None or name.split("/")[-1] != cls.__name__:
        raise TypeError(f"{cls!r} is not a message class of diffctl.client.messages")
    if "_CREATE_ROS_MESSAGE" not in vars(type(cls)):
        raise TypeError(f"{name} is a service or action, not a message: use its Request/Response/Goal/… classes")
    return name


def encoder(cls: type) -> Callable[[Any], bytes]:
    name = _typename(cls)
    return cdr.compile_encoder(types.store_described(name), name, rosidl=True)


def decoder(cls: type) -> Callable[[bytes | bytearray | memoryview], Any]:
    name = _typename(cls)
    return cdr.compile_decoder(types.store_described(name), name, MessageError, classes=classes.interface_class)
