"""`OnProcessIO`: react to what processes write (or are given to read)."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from ..events.process.process_io import ProcessIO
from ..some_entities_type import SomeEntitiesType
from .on_action_event_base import OnActionEventBase

if TYPE_CHECKING:
    from ..action import Action
    from ..launch_context import LaunchContext

IOCallback = Callable[[ProcessIO], SomeEntitiesType | None]


class OnProcessIO(OnActionEventBase):
    """Hands each chunk of `target_action`'s streams (any process's, with none) to its stream's callback.

    The callbacks take the event only; a stream without one is ignored.
    """

    def __init__(
        self,
        *,
        target_action: Callable[[Action], bool] | Action | None = None,
        on_stdin: IOCallback | None = None,
        on_stdout: IOCallback | None = None,
        on_stderr: IOCallback | None = None,
        **kwargs: Any,
    ) -> None:
        from ..actions.execute_local import ExecuteLocal

        by_stream = (('from_stdout', on_stdout), ('from_stderr', on_stderr), ('from_stdin', on_stdin))

        def route(event: ProcessIO, context: LaunchContext) -> SomeEntitiesType | None:
            for stream, callback in by_stream:
                if callback is not None and getattr(event, stream):
                    return callback(event)
            return None

        super().__init__(
            action_matcher=target_action, on_event=route, target_event_cls=ProcessIO,
            target_action_cls=ExecuteLocal, **kwargs)
