"""`Shutdown`, the event: the launch is to end."""

from __future__ import annotations

from .._private.fields import field
from ..event import Event


class Shutdown(Event):
    """Ends the launch: processes are asked to stop, timers are canceled, no new process starts.

    `due_to_sigint`: launch itself got a SIGINT (Ctrl-C), which a terminal also gave its processes.
    """

    name = 'launch.events.Shutdown'

    reason = field('reason', 'Why the launch ends.')
    due_to_sigint = field('due_to_sigint', 'Whether a SIGINT to launch started it.')

    def __init__(self, *, reason: str = 'reason not given', due_to_sigint: bool = False) -> None:
        self._fields = {'reason': reason, 'due_to_sigint': due_to_sigint}
