"""Events of `launch.events` / `launch.events.process`: what EmitEvent emits and what callables receive.

Emitted: `Shutdown(reason=…)`, `process.SignalProcess(signal_number=…, process_matcher=matches_action(node))`,
`process.ShutdownProcess(process_matcher=…)`. Received by callable handlers: `ProcessStarted`,
`ProcessExited` (`returncode`), `ProcessIO` (`text` as bytes, `from_stdout`/`from_stderr`), `Shutdown`.
"""

from __future__ import annotations

import signal as signal_module
from dataclasses import dataclass, field
from typing import Any

from diffctl.errors import LaunchError
from diffctl.launch_legacy.substitutions import SomeSubstitutions


class Event:
    """Base of every event (launch.Event); non-process events name their type by `name`, as ROS's."""


class Shutdown(Event):
    """Ask the launch to shut down, as `launch.events.Shutdown(reason=…)`."""

    name = "launch.events.Shutdown"

    def __init__(
        self, *, reason: SomeSubstitutions = "shutdown event emitted by the launch file", due_to_sigint: bool = False
    ) -> None:
        self.reason = reason  # text for handlers to read; EmitEvent substitutes it
        self.due_to_sigint = due_to_sigint


@dataclass(frozen=True)
class ProcessMatcher:
    """Which processes an event is for: one action object, or processes of a name."""

    action: Any = None
    name: str | None = None

    def __call__(self, action: Any) -> bool:
        """As launch's matchers, a predicate on an action (ChangeState takes it so)."""
        if self.action is not None:
            return action is self.action
        return getattr(action, "_process_name", None) == self.name


def matches_action(target_action: Any) -> ProcessMatcher:
    return ProcessMatcher(action=target_action)


def matches_name(name: str) -> ProcessMatcher:
    return ProcessMatcher(name=name)


def _matcher(process_matcher: Any) -> ProcessMatcher:
    if isinstance(process_matcher, ProcessMatcher):
        return process_matcher
    raise LaunchError(
        "process_matcher must be launch.events.matches_action(action) or matches_name(name)",
        hint="a lambda over process events cannot be resolved before the launch starts",
    )


class SignalProcess(Event):
    """Send a signal to the matched processes' groups (`signal_number` an int, a Signals or a name 'SIGINT')."""

    def __init__(self, *, signal_number: int | str, process_matcher: Any) -> None:
        if isinstance(signal_number, str):
            try:
                signal_number = signal_module.Signals[signal_number]
            except KeyError:
                raise LaunchError(f"SignalProcess: {signal_number!r} is not a signal name") from None
        try:
            self.signal = signal_module.Signals(int(signal_number))
        except ValueError:
            raise LaunchError(f"SignalProcess: {signal_number!r} is not a signal") from None
        self.matcher = _matcher(process_matcher)


class ShutdownProcess(Event):
    """Stop the matched processes as launch shutdown would: SIGINT, then SIGTERM, then SIGKILL."""

    def __init__(self, *, process_matcher: Any) -> None:
        self.matcher = _matcher(process_matcher)


class ExecutionComplete(Event):
    """An action's execution is complete (emitted only when some OnExecutionComplete handler would take it)."""

    name = "launch.events.ExecutionComplete"

    def __init__(self, *, action: Any) -> None:
        self.action = action


class TimerEvent(Event):
    """A TimerAction's period has passed: its actions are visited now, with the locals it started with."""

    name = "launch.events.TimerEvent"

    def __init__(self, *, timer_action: Any, locals: dict[str, Any]) -> None:
        self.timer_action = timer_action
        self.locals = locals


@dataclass
class ProcessEvent(Event):
    """What a callable handler receives about one process (the fields of launch's process events)."""

    action: Any
    name: str
    pid: int | None
    cmd: list[str] = field(default_factory=list)
    cwd: str | None = None
    env: dict[str, str] = field(default_factory=dict)

    @property
    def process_name(self) -> str:
        return self.name


@dataclass
class ProcessStarted(ProcessEvent):
    pass


@dataclass
class ProcessExited(ProcessEvent):
    returncode: int = 0


@dataclass
class ProcessIO(ProcessEvent):
    text: bytes = b""
    fd: int = 1

    @property
    def from_stdin(self) -> bool:
        return self.fd == 0

    @property
    def from_stdout(self) -> bool:
        return self.fd == 1

    @property
    def from_stderr(self) -> bool:
        return self.fd == 2


ProcessStdout = ProcessIO
ProcessStderr = ProcessIO


class IncludeLaunchDescription(Event):
    """Include a description when the event is handled (launch.events.IncludeLaunchDescription): emitted with
    EmitEvent, it is visited by the launch's own OnIncludeLaunchDescription handler, which runs last."""

    name = "launch.events.IncludeLaunchDescription"

    def __init__(self, launch_description: Any) -> None:
        self.launch_description = launch_description


_IO_NAMES = {0: "ProcessStdin", 1: "ProcessStdout", 2: "ProcessStderr"}


def event_type_name(event: Any) -> str:
    """ROS's `Event.name` of an event: its type's dotted name (diffctl's process events keep the process's
    name in `.name`, so their type name is derived from the class, and the stream for output)."""
    if isinstance(event, ProcessIO):
        return "launch.events.process." + _IO_NAMES.get(event.fd, "ProcessIO")
    if isinstance(event, ProcessEvent):
        return "launch.events.process." + type(event).__name__
    return str(getattr(type(event), "name", "launch.Event"))
