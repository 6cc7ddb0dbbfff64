"""`OnProcessExit`: react when a process exits."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from ..events.process.process_exited import ProcessExited
from ..some_entities_type import SomeEntitiesType
from .on_action_event_base import OnActionEventBase

if TYPE_CHECKING:
    from ..action import Action
    from ..launch_context import LaunchContext


class OnProcessExit(OnActionEventBase):
    """Gives `on_exit` when the process of `target_action` exits; with no target, for every process.

    `on_exit` is entities, or a callable `(event, context)` returning them.
    """

    def __init__(
        self,
        *,
        target_action: Callable[[Action], bool] | Action | None = None,
        on_exit: SomeEntitiesType | Callable[[ProcessExited, LaunchContext], SomeEntitiesType | None],
        **kwargs: Any,
    ) -> None:
        from ..actions.execute_local import ExecuteLocal

        super().__init__(
            action_matcher=target_action, on_event=on_exit, target_event_cls=ProcessExited,
            target_action_cls=ExecuteLocal, **kwargs)
