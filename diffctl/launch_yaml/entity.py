"""`Entity` of the YAML frontend: a mapping (attributes and `children`) or a list of children.

YAML values keep the types YAML gave them: `get_attr` checks them against `data_type`. Where launch_yaml
refuses a YAML scalar of another type, diffctl takes it as ROS's frontends take the same attribute in XML:
a scalar where text is expected is the text it was written as (`respawn: true` is 'true'), an integer where
a float is expected that float. Mappings read from a file know their line, and errors about them name it.
"""

from __future__ import annotations

from typing import Any

from diffctl.launch.frontend.entity import Entity as BaseEntity
from diffctl.launch.frontend.type_utils import check_is_list_entity
from diffctl.launch.utilities.type_utils import AllowedTypesType, AllowedValueType, extract_type, is_instance_of


class LocatedDict(dict):
    """A YAML mapping that remembers where it was read (`source`, `line`) and the text of its scalar values
    as written (`texts`, by key)."""

    source: str | None = None
    line: int | None = None
    texts: dict[str, str] = {}  # noqa: RUF012 (replaced per instance by the loader; read only)


_SCALARS = (bool, int, float, type(None))


def _as_text(value: Any, written: str | None) -> str:
    """A YAML scalar as text: as it was written when known, else as YAML writes it."""
    if written is not None:
        return written
    if isinstance(value, bool):
        return 'true' if value else 'false'
    return '' if value is None else str(value)


def _lenient(value: Any, data_type: Any, written: str | None) -> Any:
    """`value` as ROS's XML frontend would have read the same attribute for `data_type`; the value itself
    when no such reading exists (the caller then refuses it)."""
    try:
        scalar, is_list = extract_type(data_type)
    except ValueError:
        return value
    if not is_list and scalar is str and isinstance(value, _SCALARS):
        return _as_text(value, written)
    if not is_list and scalar is float and isinstance(value, int) and not isinstance(value, bool):
        return float(value)
    if is_list and scalar is str and isinstance(value, list) and all(isinstance(v, (*_SCALARS, str)) for v in value):
        return [v if isinstance(v, str) else _as_text(v, None) for v in value]
    return value


class Entity(BaseEntity):
    """One entity of a YAML launch file."""

    def __init__(self, element: Any, type_name: str | None = None, *, parent: Entity | None = None) -> None:
        self.__type_name = type_name
        self.__element = element
        self.__parent = parent
        self.__read_keys: set = set()
        self.__children_called = False

    @property
    def type_name(self) -> str | None:
        return self.__type_name

    @property
    def parent(self) -> Entity | None:
        return self.__parent

    @property
    def location(self) -> str | None:
        """'file:line' of the entity, when it was read from a file."""
        line = getattr(self.__element, 'line', None)
        if line is None and self.__parent is not None:
            return self.__parent.location
        return None if line is None else f'{self.__element.source}:{line}'

    @property
    def yaml_value(self) -> Any:
        """diffctl's: the YAML value the entity wraps (a mapping, a list of children, a scalar), as read."""
        return self.__element

    def get_yaml_attr(self, name: str, *, optional: bool = False) -> Any:
        """diffctl's: the YAML value of key `name` as read, whatever its type (a mapping too: `get_attr` returns
        only what ROS's frontends share, scalars and lists), marked as read. None when absent and `optional`."""
        if name not in self.__element:
            if optional:
                return None
            raise AttributeError(f"{self.__where()}Can not find attribute '{name}' in Entity '{self.type_name}'")
        self.__read_keys.add(name)
        return self.__element[name]

    def __where(self) -> str:
        location = self.location
        return f'{location}: ' if location else ''

    @property
    def children(self) -> list[Entity]:
        self.__children_called = True
        element = self.__element
        if not isinstance(element, (dict, list)):
            raise TypeError(f'{self.__where()}Expected a dict or list, got {type(element)}:\n---\n{element}\n---')
        if isinstance(element, dict):
            if 'children' not in element:
                raise ValueError(
                    f'{self.__where()}Expected entity `{self.__type_name}` to have children entities.'
                    'That can be a list of subentities or a dictionary with a `children` list element')
            self.__read_keys.add('children')
            children = element['children']
        else:
            children = element
        entities = []
        for child in children:
            if not isinstance(child, dict) or len(child) != 1:
                raise RuntimeError(
                    f'{self.__where()}Subentities must be a dictionary with only one key, which is the entity type')
            (type_name, body), = child.items()
            entities.append(Entity(body, type_name, parent=self))
        return entities

    def assert_entity_completely_parsed(self) -> None:
        element = self.__element
        if isinstance(element, list):
            if not self.__children_called:
                raise ValueError(
                    f'{self.__where()}Unexpected nested entity(ies) found in `{self.__type_name}`: {element}')
            return
        unread = set(element.keys()) - self.__read_keys
        if unread:
            raise ValueError(f'{self.__where()}Unexpected key(s) found in `{self.__type_name}`: {unread}')

    def get_attr(
        self,
        name: str,
        *,
        data_type: AllowedTypesType = str,
        optional: bool = False,
        can_be_str: bool = True,
    ) -> AllowedValueType | list[Entity] | None:
        """The value of key `name`, checked to be a `data_type` (or a list of mappings for `List[Entity]`).

        See `launch.frontend.Entity.get_attr`; YAML values are not coerced.
        """
        if name not in self.__element:
            if optional:
                return None
            raise AttributeError(
                f"{self.__where()}Can not find attribute '{name}' in Entity '{self.type_name}'")
        self.__read_keys.add(name)
        data = self.__element[name]
        if check_is_list_entity(data_type):
            if isinstance(data, list) and data and isinstance(data[0], dict):
                return [Entity(child, name, parent=self) for child in data]
            raise TypeError(
                f"{self.__where()}Attribute '{name}' of Entity '{self.type_name}' "
                'expected to be a list of dictionaries.')
        if not is_instance_of(data, data_type, can_be_str=can_be_str):
            data = _lenient(data, data_type, getattr(self.__element, 'texts', {}).get(name))
        if not is_instance_of(data, data_type, can_be_str=can_be_str):
            raise TypeError(
                f"{self.__where()}Attribute '{name}' of Entity '{self.type_name}' expected to be of type "
                f"'{data_type}', got '{type(data)}'")
        return data
