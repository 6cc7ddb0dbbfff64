"""What every process of a launch has done so far, by name: started, exited (with its code).

Readiness conditions (readiness.py) name processes that may have started, or even ended, before the condition
is reached, and a process event is seen only by the handlers registered when it happens. So one handler,
installed when the launch starts (`install`, which `diffctl launch` calls first) or else when the first
condition is reached, records every process's start and exit for the conditions that come later.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

from diffctl.launch import LaunchContext
from diffctl.launch.event_handler import BaseEventHandler
from diffctl.launch.events.process import ProcessExited, ProcessStarted

GLOBAL_KEY = "diffctl_process_watch"
_COUNTER = re.compile(r"-\d+$")


def process_names(action: Any, event_name: str | None = None) -> set[str]:
    """The names a launch file may call a process by: its label (with and without the `-N` that ros2 launch
    appends), and a Node's node name (fully qualified and bare)."""
    names: set[str] = set()
    label = event_name
    if label is None:
        details = getattr(action, "process_details", None)
        label = details.get("name") if isinstance(details, dict) else None
    if label:
        names |= {label, _COUNTER.sub("", label)}
    try:
        node = getattr(action, "node_name", None)
    except RuntimeError:  # launch_ros raises before the Node is executed
        node = None
    if isinstance(node, str) and node:
        bare = node.rsplit("/", 1)[-1]
        if "<" not in bare:  # launch_ros writes a placeholder for a name it was not given
            names.add(bare)
        if "<" not in node:
            names.add(node)
    return names


@dataclass
class ProcessRecord:
    starts: int = 0
    running: bool = False
    returncode: int | None = None
    actions: list[Any] = field(default_factory=list)


class ProcessWatch(BaseEventHandler):
    """The launch's process history, kept by name and by action (a handler of every start and exit)."""

    def __init__(self) -> None:
        super().__init__(matcher=lambda event: isinstance(event, (ProcessStarted, ProcessExited)))
        self.by_name: dict[str, ProcessRecord] = {}
        self.by_action: dict[int, ProcessRecord] = {}

    def handle(self, event: Any, context: LaunchContext) -> None:
        super().handle(event, context)
        for record in self._records(event.action, event.process_name):
            if isinstance(event, ProcessStarted):
                record.starts += 1
                record.running = True
                record.returncode = None
            else:
                record.running = False
                record.returncode = event.returncode
        return None

    def _records(self, action: Any, name: str | None) -> list[ProcessRecord]:
        records = [self.by_action.setdefault(id(action), ProcessRecord(actions=[action]))]
        for n in process_names(action, name):
            record = self.by_name.setdefault(n, ProcessRecord())
            if action not in record.actions:
                record.actions.append(action)
            records.append(record)
        return records

    def of_action(self, action: Any) -> ProcessRecord | None:
        return self.by_action.get(id(action))

    def of_name(self, name: str) -> ProcessRecord | None:
        return self.by_name.get(name)

    @property
    def handler_description(self) -> str:
        return "<diffctl process watch>"


def install(context: LaunchContext) -> ProcessWatch:
    """The launch's watch, registered on first use (the oldest handler then, so it sees every event)."""
    watch = context.get_locals_as_dict().get(GLOBAL_KEY)
    if isinstance(watch, ProcessWatch):
        return watch
    watch = ProcessWatch()
    context.register_event_handler(watch, append=True)
    context.extend_globals({GLOBAL_KEY: watch})
    return watch
