"""`TimerEvent`: a timer's delay is over."""

from __future__ import annotations

from typing import TYPE_CHECKING

from .._private.fields import field
from ..event import Event

if TYPE_CHECKING:
    from ..actions.timer_action import TimerAction


class TimerEvent(Event):
    """Emitted by a `TimerAction` that was not canceled in time."""

    name = 'launch.events.TimerEvent'

    timer_action = field('timer_action', 'The timer whose delay is over.')

    def __init__(self, *, timer_action: TimerAction) -> None:
        self._fields = {'timer_action': timer_action}
