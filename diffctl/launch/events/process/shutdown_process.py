"""`ShutdownProcess`: ask processes to shut down (SIGINT, then SIGTERM and SIGKILL if they linger)."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from .process_targeted_event import ProcessTargetedEvent

if TYPE_CHECKING:
    from ...actions.execute_local import ExecuteLocal


class ShutdownProcess(ProcessTargetedEvent):
    """Starts the shutdown of the matched processes, as `ExecuteLocal` does on launch shutdown."""

    name = 'launch.events.process.ShutdownProcess'

    def __init__(self, *, process_matcher: Callable[[ExecuteLocal], bool]) -> None:
        super().__init__(process_matcher=process_matcher)
