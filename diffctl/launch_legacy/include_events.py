"""OnIncludeLaunchDescription and event_named, as ros2/launch's `launch.event_handlers` defines them.

ROS's LaunchService registers one OnIncludeLaunchDescription first thing, so an emitted
`events.IncludeLaunchDescription` is visited after every handler registered later (the engine does that
itself, see Engine._handle); a launch file may register more of them, each visiting the description again
as ROS's would. `event_named(name)` matches events by ROS's type name (`launch.events.process.ProcessExited`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from diffctl.launch_legacy import events
from diffctl.launch_legacy.event_actions import OpaqueFunction
from diffctl.launch_legacy.event_handlers import BaseEventHandler


def _the_included(context: Any) -> list[Any]:
    return [context.locals.event.launch_description]


class OnIncludeLaunchDescription(BaseEventHandler):
    kind = "include"
    event_type = events.IncludeLaunchDescription

    def __init__(self, **kw: Any) -> None:
        super().__init__(entities=[OpaqueFunction(function=_the_included)], **kw)


def event_named(name: str) -> Callable[[Any], bool]:
    """A matcher of events whose ROS type name is `name` (for EventHandler(matcher=…))."""
    return lambda event: events.event_type_name(event) == name
