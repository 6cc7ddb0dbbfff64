"""Type helpers for frontends: `List[Entity]` attributes, and the `type` attribute's names."""

from __future__ import annotations

from typing import Any, List

from ..utilities.type_utils import is_typing_list
from .entity import Entity

# what a frontend's `type="…"` names; 'yaml' reads the value by YAML's rules
_NAMED_TYPES: dict[str, Any] = {
    **{name: kind for kind in (str, bool, float, int) for name in (kind.__name__,)},
    **{f'list_of_{kind.__name__}': List[kind] for kind in (str, bool, float, int)},
    'yaml': None,
}


def check_is_list_entity(data_type: Any) -> bool:
    """Whether `data_type` is `List[E]` for `Entity` or one of its subclasses: nested elements are wanted."""
    if not is_typing_list(data_type):
        return False
    item = (getattr(data_type, '__args__', None) or (None,))[0]
    return isinstance(item, type) and issubclass(item, Entity)


def get_data_type_from_identifier(type_identifier: str):
    """The data type a `type` attribute names ('int', 'list_of_str', 'yaml', …); ValueError for others."""
    try:
        return _NAMED_TYPES[type_identifier]
    except KeyError:
        raise ValueError(f"Got invalid type identifier '{type_identifier}'") from None
