"""Type helpers for frontend implementations."""

from __future__ import annotations

from typing import Any, List

from ..utilities.type_utils import is_typing_list
from .entity import Entity


def check_is_list_entity(data_type: Any) -> bool:
    """True for `List[E]` where E is `Entity` or a subclass of it."""
    if not is_typing_list(data_type):
        return False
    args = getattr(data_type, '__args__', None) or ()
    return bool(args) and isinstance(args[0], type) and issubclass(args[0], Entity)


_TYPES = {
    'str': str,
    'bool': bool,
    'float': float,
    'int': int,
    'list_of_str': List[str],
    'list_of_bool': List[bool],
    'list_of_float': List[float],
    'list_of_int': List[int],
    'yaml': None,
}


def get_data_type_from_identifier(type_identifier: str):
    """The data type named by a frontend's `type` attribute ('int', 'list_of_str', 'yaml', …)."""
    if type_identifier not in _TYPES:
        raise ValueError(f"Got invalid type identifier '{type_identifier}'")
    return _TYPES[type_identifier]
