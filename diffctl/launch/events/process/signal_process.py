"""`SignalProcess`: send a signal to processes."""

from __future__ import annotations

import signal as signal_module
from collections.abc import Callable
from typing import TYPE_CHECKING

from ...utilities.ensure_argument_type_impl import ensure_argument_type
from .process_targeted_event import ProcessTargetedEvent

if TYPE_CHECKING:
    from ...actions.execute_local import ExecuteLocal


class SignalProcess(ProcessTargetedEvent):
    """Send `signal_number` (a `signal.Signals`, or the string 'SIGKILL') to the matched processes."""

    name = 'launch.events.process.SignalProcess'

    def __init__(
        self, *, signal_number: str | signal_module.Signals, process_matcher: Callable[[ExecuteLocal], bool]
    ) -> None:
        super().__init__(process_matcher=process_matcher)
        ensure_argument_type(signal_number, (str, signal_module.Signals), 'signal_number', 'SignalProcess')
        self.__signal = signal_number

    @property
    def signal(self) -> str | signal_module.Signals:
        """The signal as given."""
        return self.__signal

    @property
    def signal_name(self) -> str:
        """Its name, e.g. 'SIGINT'."""
        return self.__signal if isinstance(self.__signal, str) else self.__signal.name
