"""`ProcessTargetedEvent`: an event addressed to some of the running process actions."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from ..._private.fields import field
from ...event import Event

if TYPE_CHECKING:
    from ...actions.execute_local import ExecuteLocal


class ProcessTargetedEvent(Event):
    """Every process action asks `process_matcher(itself)` whether the event is for it (`matches_*`)."""

    name = 'launch.events.process.ProcessTargetedEvent'

    process_matcher = field('process_matcher', 'The predicate choosing the process actions addressed.')

    def __init__(self, *, process_matcher: Callable[[ExecuteLocal], bool]) -> None:
        super().__init__()
        self._fields = {'process_matcher': process_matcher}
