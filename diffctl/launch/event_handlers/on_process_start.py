"""`OnProcessStart`: react when a process starts (its pid is known)."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from ..events.process.process_started import ProcessStarted
from ..some_entities_type import SomeEntitiesType
from .on_action_event_base import OnActionEventBase

if TYPE_CHECKING:
    from ..action import Action
    from ..launch_context import LaunchContext


class OnProcessStart(OnActionEventBase):
    """Gives `on_start` when the process of `target_action` starts (its pid is known); any process without one.

    `on_start` is entities, or a callable `(event, context)` returning them.
    """

    def __init__(
        self,
        *,
        target_action: Callable[[Action], bool] | Action | None = None,
        on_start: SomeEntitiesType | Callable[[ProcessStarted, LaunchContext], SomeEntitiesType | None],
        **kwargs: Any,
    ) -> None:
        from ..actions.execute_process import ExecuteProcess

        super().__init__(
            action_matcher=target_action, on_event=on_start, target_event_cls=ProcessStarted,
            target_action_cls=ExecuteProcess, **kwargs)
