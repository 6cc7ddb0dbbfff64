"""set_message_fields: a message's fields from a (nested) dict, converted as rosidl_runtime_py converts them."""

from __future__ import annotations

import array
from functools import partial
from typing import Any

import numpy

from diffctl.interfaces.definition import AbstractNestedType, NamespacedType
from diffctl.interfaces.runtime.convert import get_message_slot_types
from diffctl.interfaces.runtime.names import import_message_from_namespaced_type


def set_message_fields(msg: Any, values: dict[str, Any], expand_header_auto: bool = False,
                       expand_time_now: bool = False) -> list[Any]:
    """Set `msg`'s fields from `values`; returns setters for the stamps given as 'auto' (a Header) or 'now'
    (a Time) when those expansions are on. AttributeError for an unknown field, TypeError for a value
    that does not fit."""
    stamps: list[Any] = []
    _set(msg, values, stamps, expand_header_auto, expand_time_now)
    return stamps


def _set(msg: Any, values: Any, stamps: list[Any], header_auto: bool, time_now: bool) -> None:
    try:
        items = values.items()
    except AttributeError:
        raise TypeError(f"Value '{values}' is expected to be a dictionary but is a {type(values).__name__}") from None
    for name, given in items:
        field = getattr(msg, name)
        field_type = type(field)
        qualified = f"{field_type.__module__}.{field_type.__name__}"
        if field_type is array.array:
            value = field_type(field.typecode, given)
        elif field_type is numpy.ndarray:
            value = numpy.array(given, dtype=field.dtype)
        elif type(given) is field_type:
            value = given
        elif qualified == "std_msgs.msg._header.Header" and given == "auto" and header_auto:
            stamps.append(partial(setattr, field, "stamp"))
            continue
        elif qualified == "builtin_interfaces.msg._time.Time" and given == "now" and time_now:
            stamps.append(partial(setattr, msg, name))
            continue
        else:
            try:
                value = field_type(given)
            except TypeError:
                value = field_type()
                _set(value, given, stamps, header_auto, time_now)
        slot = get_message_slot_types(msg)[name]
        if isinstance(slot, AbstractNestedType) and isinstance(slot.value_type, NamespacedType):
            element = import_message_from_namespaced_type(slot.value_type)
            for i in range(len(value)):
                sub = element()
                _set(sub, value[i], stamps, header_auto, time_now)
                value[i] = sub
        setattr(msg, name, value)
