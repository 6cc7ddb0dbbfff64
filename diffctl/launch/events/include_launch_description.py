"""`IncludeLaunchDescription`, the event: a launch description for the running launch to visit."""

from __future__ import annotations

from typing import TYPE_CHECKING

from .._private.fields import field
from ..event import Event

if TYPE_CHECKING:
    from ..launch_description import LaunchDescription


class IncludeLaunchDescription(Event):
    """Carries a description to visit; `LaunchService.include_launch_description` emits one."""

    name = 'launch.events.IncludeLaunchDescription'

    launch_description = field('launch_description', 'The description to visit.')

    def __init__(self, launch_description: LaunchDescription) -> None:
        self._fields = {'launch_description': launch_description}
