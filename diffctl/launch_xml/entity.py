"""`Entity` of the XML frontend: an XML element.

Attributes are text, coerced to the type asked for (`get_attr(..., data_type=int)`); `name-sep="sep"` next
to an attribute makes it a list split on `sep`. `List[Entity]` reads the child elements of that tag.
Elements read from a file know their line, and errors about them name it.
"""

from __future__ import annotations

import weakref
import xml.etree.ElementTree as ET

from diffctl.launch.frontend.entity import Entity as BaseEntity
from diffctl.launch.frontend.type_utils import check_is_list_entity
from diffctl.launch.utilities.type_utils import AllowedTypesType, AllowedValueType, get_typed_value

# element -> (file, line), for elements read by Parser.load
_locations: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def remember_location(element: ET.Element, source: str, line: int) -> None:
    """Record where an element was read from (used by the XML parser)."""
    _locations[element] = (source, line)


class Entity(BaseEntity):
    """One XML element of a launch file."""

    def __init__(self, xml_element: ET.Element | None = None, *, parent: Entity | None = None) -> None:
        self.__xml_element = xml_element
        self.__parent = parent
        self.__read_attributes: set = set()
        self.__read_children: set = set()

    @property
    def type_name(self) -> str:
        return self.__xml_element.tag

    @property
    def parent(self) -> Entity | None:
        return self.__parent

    @property
    def location(self) -> str | None:
        """'file:line' of the element, when it was read from a file."""
        where = _locations.get(self.__xml_element)
        return None if where is None else f'{where[0]}:{where[1]}'

    def __where(self) -> str:
        location = self.location
        return f'{location}: ' if location else ''

    @property
    def children(self) -> list[Entity]:
        self.__read_children = {child.tag for child in self.__xml_element}
        return [Entity(child, parent=self) for child in self.__xml_element]

    def assert_entity_completely_parsed(self) -> None:
        tag = self.__xml_element.tag
        unread_children = {child.tag for child in self.__xml_element} - self.__read_children
        if unread_children:
            raise ValueError(f'{self.__where()}Unexpected nested tag(s) found in `{tag}`: {unread_children}')
        unread_attributes = set(self.__xml_element.attrib) - self.__read_attributes
        if unread_attributes:
            raise ValueError(f'{self.__where()}Unexpected attribute(s) found in `{tag}`: {unread_attributes}')

    def get_attr(
        self,
        name: str,
        *,
        data_type: AllowedTypesType = str,
        optional: bool = False,
        can_be_str: bool = True,
    ) -> AllowedValueType | list[Entity] | None:
        """An attribute coerced to `data_type`, or the child elements `name` for `List[Entity]`.

        See `launch.frontend.Entity.get_attr`. A value that does not convert is a TypeError.
        """
        if check_is_list_entity(data_type):
            children = [child for child in self.__xml_element if child.tag == name]
            if not children:
                if optional:
                    return None
                raise self.__missing(name, data_type)
            self.__read_children.add(name)
            return [Entity(child, parent=self) for child in children]
        attributes = self.__xml_element.attrib
        if name not in attributes:
            if optional:
                return None
            raise self.__missing(name, data_type)
        self.__read_attributes.add(name)
        value: str | list[str] = attributes[name]
        separator = attributes.get(name + '-sep')
        if separator is not None:
            self.__read_attributes.add(name + '-sep')
            value = value.split(separator)
        try:
            return get_typed_value(value, data_type, can_be_str=can_be_str)
        except ValueError:
            raise TypeError(
                f"{self.__where()}Attribute '{name}' of Entity '{self.type_name}' expected to be of type "
                f"'{data_type}'.'{value}' can not be converted to one of those types") from None

    def __missing(self, name: str, data_type: object) -> AttributeError:
        return AttributeError(
            f"{self.__where()}Attribute '{name}' of type '{data_type}' not found in Entity '{self.type_name}'")
