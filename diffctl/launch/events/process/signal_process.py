"""`SignalProcess`: send a signal to processes."""

from __future__ import annotations

import signal as signals
from collections.abc import Callable
from typing import TYPE_CHECKING

from ..._private.fields import field
from ...utilities.ensure_argument_type_impl import ensure_argument_type
from .process_targeted_event import ProcessTargetedEvent

if TYPE_CHECKING:
    from ...actions.execute_local import ExecuteLocal


class SignalProcess(ProcessTargetedEvent):
    """The processes addressed get `signal_number`: a `signal.Signals`, or 'SIGKILL' spelled as text."""

    name = 'launch.events.process.SignalProcess'

    signal = field('signal', 'The signal as given.')

    def __init__(
        self, *, signal_number: str | signals.Signals, process_matcher: Callable[[ExecuteLocal], bool]
    ) -> None:
        super().__init__(process_matcher=process_matcher)
        ensure_argument_type(signal_number, (str, signals.Signals), 'signal_number', 'SignalProcess')
        self._fields['signal'] = signal_number

    @property
    def signal_name(self) -> str:
        """The signal's name, such as 'SIGINT'."""
        given = self._fields['signal']
        return given if isinstance(given, str) else given.name
