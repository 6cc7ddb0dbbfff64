"""`LaunchDescriptionEntity`: the base of everything a launch description holds."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import asyncio

    from .launch_context import LaunchContext


class LaunchDescriptionEntity:
    """One item of a launch description: an action, a launch description, or anything visitable.

    Two walks use these methods. Describing (``ros2 launch --print``, argument discovery) calls
    `describe`, `describe_sub_entities` and `describe_conditional_sub_entities` and needs no context.
    Launching calls `visit` with the `LaunchContext`; the entities it returns are visited next, and
    `get_asyncio_future` tells the service whether this entity still has work in flight.
    """

    def describe(self) -> str:
        """Text describing this entity; subclasses provide it."""
        raise NotImplementedError()

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        """Entities always produced when this one is visited (empty by default)."""
        return []

    def describe_conditional_sub_entities(self) -> list[tuple[str, Iterable[LaunchDescriptionEntity]]]:
        """(condition text, entities) pairs: entities produced only when that condition holds."""
        return []

    def visit(self, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        """Do this entity's work in `context` and return entities to visit next, or None.

        Runs on the launch loop: it must not block. Long work belongs in a task on
        `context.asyncio_loop`, reported through `get_asyncio_future`.
        """
        return None

    def get_asyncio_future(self) -> asyncio.Future | None:
        """A future done when this entity's asynchronous work is over, or None when it has none."""
        return None
