"""`normalize_to_list_of_entities`: entities and groups of entities as one flat list."""

from __future__ import annotations

import itertools
from collections.abc import Iterable

from ..launch_description_entity import LaunchDescriptionEntity
from ..some_entities_type import SomeEntitiesType


def normalize_to_list_of_entities(entities: Iterable[SomeEntitiesType]) -> list[LaunchDescriptionEntity]:
    """Each item an entity, or an iterable of entities unpacked in its place (one level only)."""
    return list(itertools.chain.from_iterable(
        (item,) if isinstance(item, LaunchDescriptionEntity) else item for item in entities))
