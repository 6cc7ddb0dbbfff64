"""`Shutdown`, `<shutdown [reason=…]/>`: end the launch."""

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


@expose_action('shutdown')
class Shutdown(EmitEvent):
    """Emits `launch.events.Shutdown(reason=reason)`.

    Run by an `on_exit` of a process (the "required node" idiom), it says which process ended the launch.
    """

    def __init__(self, *, reason: str = 'reason not given', **kwargs: Any) -> None:
        super().__init__(event=ShutdownEvent(reason=reason), **kwargs)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        _, kwargs = super().parse(entity, parser)
        reason = entity.get_attr('reason', optional=True)
        if reason:  # an empty reason keeps the default
            kwargs['reason'] = parser.parse_substitution(reason)
        return cls, kwargs

    def execute(self, context: LaunchContext) -> None:
        cause = context.get_locals_as_dict().get('event')
        if isinstance(cause, ProcessExited):
            # the plain 'launch' logger, as in ROS 2: this line has no launch.log handler of its own
            logging.getLogger('launch').info(
                f'process[{cause.process_name}] was required: shutting down launched system')
        super().execute(context)
