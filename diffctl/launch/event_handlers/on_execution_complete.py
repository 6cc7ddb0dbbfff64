"""`OnExecutionComplete`: react when an action is done."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from ..events.execution_complete import ExecutionComplete
from ..some_entities_type import SomeEntitiesType
from .on_action_event_base import OnActionEventBase

if TYPE_CHECKING:
    from ..action import Action
    from ..launch_context import LaunchContext


class OnExecutionComplete(OnActionEventBase):
    """Gives `on_completion` when `target_action` (any action, with none) completes.

    Registering one is what makes actions emit ExecutionComplete at all.
    """

    def __init__(
        self,
        *,
        target_action: Callable[[Action], bool] | Action | None = None,
        on_completion: SomeEntitiesType | Callable[[ExecutionComplete, LaunchContext], SomeEntitiesType | None],
        **kwargs: Any,
    ) -> None:
        from ..action import Action

        super().__init__(
            action_matcher=target_action, on_event=on_completion, target_event_cls=ExecutionComplete,
            target_action_cls=Action, **kwargs)
