"""`Entity`: one element of a markup launch file (an XML tag, a YAML mapping), as the parser sees it."""

from __future__ import annotations

from typing import TypeVar

TargetType = TypeVar('TargetType')


class Entity:
    """Interface every frontend's entity implements.

    `type_name` is the tag (`executable`, `arg`, …), `children` the nested entities, and `get_attr` reads
    an attribute as `data_type` (`str` by default; `None` reads it with YAML rules; `List[Entity]` reads
    nested entities of that name). A missing attribute raises AttributeError unless `optional`, a value of
    the wrong type TypeError or ValueError. After an action's `parse`, `assert_entity_completely_parsed`
    raises when some attribute or child was never read.
    """

    @property
    def type_name(self) -> str:
        raise NotImplementedError()

    @property
    def parent(self) -> Entity | None:
        raise NotImplementedError()

    @property
    def children(self) -> list[Entity]:
        raise NotImplementedError()

    def get_attr(self, name, *, data_type=str, optional=False, can_be_str=True):
        raise NotImplementedError()

    def assert_entity_completely_parsed(self):
        raise NotImplementedError()
