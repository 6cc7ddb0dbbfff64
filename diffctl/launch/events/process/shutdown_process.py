"""`ShutdownProcess`: ask processes to stop, with the escalation a launch shutdown uses."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from .process_targeted_event import ProcessTargetedEvent

if TYPE_CHECKING:
    from ...actions.execute_local import ExecuteLocal


class ShutdownProcess(ProcessTargetedEvent):
    """The processes addressed get SIGINT, then SIGTERM and SIGKILL while they linger."""

    name = 'launch.events.process.ShutdownProcess'

    def __init__(self, *, process_matcher: Callable[[ExecuteLocal], bool]) -> None:
        super().__init__(process_matcher=process_matcher)
