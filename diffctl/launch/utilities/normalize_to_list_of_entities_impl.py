"""`normalize_to_list_of_entities`: flatten entities and iterables of entities into one list."""

from __future__ import annotations

from collections.abc import Iterable

from ..launch_description_entity import LaunchDescriptionEntity
from ..some_entities_type import SomeEntitiesType


def normalize_to_list_of_entities(entities: Iterable[SomeEntitiesType]) -> list[LaunchDescriptionEntity]:
    """One flat list from items that are entities or iterables of entities (one level deep)."""
    flat: list[LaunchDescriptionEntity] = []
    for item in entities:
        if isinstance(item, LaunchDescriptionEntity):
            flat.append(item)
        else:
            flat.extend(item)
    return flat
