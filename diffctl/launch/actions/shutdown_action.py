"""`Shutdown` (`<shutdown>`): end the launch."""

from __future__ import annotations

import logging
from typing import TYPE_CHECKING, Any

from ..events.process.process_exited import ProcessExited
from ..events.shutdown import Shutdown as ShutdownEvent
from ..frontend.expose import expose_action
from .emit_event import EmitEvent

if TYPE_CHECKING:
    from ..frontend.entity import Entity
    from ..frontend.parser import Parser
    from ..launch_context import LaunchContext

_logger = logging.getLogger(name='launch')


@expose_action('shutdown')
class Shutdown(EmitEvent):
    """Emits a `launch.events.Shutdown` event with `reason`."""

    def __init__(self, *, reason: str = 'reason not given', **kwargs: Any) -> None:
        super().__init__(event=ShutdownEvent(reason=reason), **kwargs)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        _, kwargs = super().parse(entity, parser)
        reason = entity.get_attr('reason', optional=True)
        if reason:
            kwargs['reason'] = parser.parse_substitution(reason)
        return cls, kwargs

    def execute(self, context: LaunchContext) -> None:
        event = context.get_locals_as_dict().get('event')
        if isinstance(event, ProcessExited):
            _logger.info(f'process[{event.process_name}] was required: shutting down launched system')
        super().execute(context)
