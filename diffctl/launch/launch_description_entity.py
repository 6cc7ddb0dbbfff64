"""`LaunchDescriptionEntity`: anything a launch description may hold."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

from ._private.ros_names import default_text

if TYPE_CHECKING:
    import asyncio

    from .launch_context import LaunchContext


class LaunchDescriptionEntity:
    """An item of a launch description: an action, a description, or any visitable thing.

    Two walks use an entity. Describing (`ros2 launch --print`, finding the arguments) needs no context:
    `describe`, `describe_sub_entities`, `describe_conditional_sub_entities`. Launching calls
    `visit(context)`, then visits what it returned, and watches `get_asyncio_future()` for work in flight.
    """

    def __repr__(self) -> str:
        return default_text(self)  # under ROS's module names, as ros2 launch --print shows it

    def describe(self) -> str:
        """This entity in words; every kind of entity says it."""
        raise NotImplementedError()

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        """The entities visiting this one always gives (none here)."""
        return []

    def describe_conditional_sub_entities(self) -> list[tuple[str, Iterable[LaunchDescriptionEntity]]]:
        """(the condition in words, the entities given when it holds) pairs (none here)."""
        return []

    def visit(self, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        """Do this entity's part and return the entities to visit next (None: nothing).

        It runs on the launch's loop and must not block; longer work goes in a task on
        `context.asyncio_loop`, announced by `get_asyncio_future`.
        """
        return None

    def get_asyncio_future(self) -> asyncio.Future | None:
        """The future of this entity's unfinished work; None when there is none."""
        return None
