"""`ExecutionComplete`: an action is done, asynchronous part included."""

from __future__ import annotations

from typing import TYPE_CHECKING

from .._private.fields import field
from ..event import Event

if TYPE_CHECKING:
    from ..action import Action


class ExecutionComplete(Event):
    """Emitted for an action once it executed and its future (if any) is done, when a handler wants it."""

    name = 'launch.events.ExecutionComplete'

    action = field('action', 'The action that completed.')

    def __init__(self, *, action: Action) -> None:
        self._fields = {'action': action}
