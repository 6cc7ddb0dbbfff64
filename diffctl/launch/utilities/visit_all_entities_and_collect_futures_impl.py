"""`visit_all_entities_and_collect_futures`: the launch service's depth-first visit."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import asyncio

    from ..launch_context import LaunchContext
    from ..launch_description_entity import LaunchDescriptionEntity


def visit_all_entities_and_collect_futures(
    entity: LaunchDescriptionEntity, context: LaunchContext
) -> list[tuple[LaunchDescriptionEntity, asyncio.Future]]:
    """Visit `entity`, then what it returned, depth first; (entity, future) for work still in flight.

    Each entity's future is asked right after its own visit, before its sub-entities are visited.
    """
    pending: list[tuple[LaunchDescriptionEntity, asyncio.Future]] = []
    stack = [entity]
    while stack:
        current = stack.pop()
        sub_entities = current.visit(context)
        future = current.get_asyncio_future()
        if future is not None:
            pending.append((current, future))
        if sub_entities is not None:
            stack.extend(reversed(list(sub_entities)))
    return pending
