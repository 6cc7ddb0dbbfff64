"""Plan data: the steps the engine asks the supervisor for (start a process, log, shut down, signal) and
what a dry run of the engine records for `--print`.

A dry run (resolver.py) gives plain data: process specs with their final command lines, and the steps that
start them, possibly behind a readiness gate, inside a timer or an event handler (those previewed as of the
moment they are registered; at run time they are evaluated when they fire).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, Literal

WaitKind = Literal["started", "exited", "log", "topic", "service"]
WAIT_KINDS: tuple[str, ...] = ("started", "exited", "log", "topic", "service")
PROCESS_WAIT_KINDS = ("started", "exited", "log")
OUTPUTS = ("screen", "log", "both")


@dataclass(frozen=True)
class Where:
    """Where an entity was written: file, line and column (YAML) or file and line (Python)."""

    source: str | None = None
    line: int | None = None
    column: int | None = None

    def __str__(self) -> str:
        if not self.source:
            return ""
        from diffctl.source_paths import user_source

        text = user_source(self.source)  # the file under src/, not its link in diffctl's cache
        if self.line is not None:
            text += f":{self.line}"
            if self.column is not None:
                text += f":{self.column}"
        return text

    def attach(self, error: Any, what: str | None = None) -> Any:
        """Give a location-less DiffctlError this location and the entity it concerns."""
        if error.source is None and self.source:
            error.source, error.line, error.column = self.source, self.line, self.column
        if what and error.field is None:
            error.field = what
        return error


@dataclass
class TargetRef:
    """A process named in a handler or readiness condition, linked to a process name after resolution.

    YAML names processes by string; Python passes the action object, known here by `origin` (its id()).
    """

    name: str | None = None
    origin: int | None = None
    where: str = ""
    label: str = ""  # what the user wrote, for messages

    def __str__(self) -> str:
        return self.name or self.label or "?"


@dataclass(frozen=True)
class Wait:
    """One readiness condition: a process started / exited with 0 / printed a line; a topic / service is up."""

    kind: str
    target: TargetRef | str  # TargetRef for process kinds, the topic or service name otherwise
    pattern: str | None = None

    def describe(self) -> str:
        if self.kind == "started":
            return f"{self.target} started"
        if self.kind == "exited":
            return f"{self.target} exited with code 0"
        if self.kind == "log":
            return f"{self.target} printed /{self.pattern}/"
        if self.kind == "topic":
            return f"topic {self.target} has a publisher"
        return f"service {self.target} answers"


@dataclass(frozen=True)
class Gate:
    waits: tuple[Wait, ...]
    timeout_s: float | None = None

    def merged(self, outer: Gate | None) -> Gate:
        if outer is None:
            return self
        timeouts = [t for t in (self.timeout_s, outer.timeout_s) if t is not None]
        return Gate(outer.waits + self.waits, min(timeouts) if timeouts else None)


@dataclass(frozen=True)
class RosNode:
    """What makes a process a ROS node: its name, namespace, parameters and remappings.

    `global_params` are SetParameter's `(name, value)` pairs (passed as `-p name:=value`) and
    SetParametersFromFile's paths, before the node's own `params`, as launch_ros orders them.
    """

    node_name: str | None
    namespace: str | None
    params: tuple[str | Mapping[str, Any], ...] = ()  # parameter files and inline dicts, in order
    remaps: tuple[tuple[str, str], ...] = ()
    global_params: tuple[tuple[str, str] | str, ...] = ()
    # launch_ros passes `__ns` (even `/`) once a namespace was given or pushed, never otherwise
    namespace_given: bool = False


@dataclass(frozen=True)
class ProcessSpec:
    name: str
    argv: tuple[str, ...]
    shell: bool = False
    cwd: str | None = None
    env: Mapping[str, str | None] = field(default_factory=dict)  # changes to the launcher's environment
    env_replace: bool = False  # `env` is the whole environment (ExecuteProcess(env=…))
    output: str = "screen"
    respawn: bool = False
    respawn_delay_s: float = 0.0
    respawn_max_retries: int = -1
    required: bool = False
    sigterm_timeout_s: float = 5.0
    sigkill_timeout_s: float = 5.0
    interactive: bool = False
    node: RosNode | None = None
    package: str | None = None
    executable: str | None = None
    where: str = ""
    origin: int = field(default=0, compare=False)


@dataclass(frozen=True, kw_only=True)
class Step:
    gate: Gate | None = None
    where: str = ""

    def with_gate(self, gate: Gate) -> Step:
        from dataclasses import replace

        return replace(self, gate=gate.merged(self.gate) if self.gate else gate)


@dataclass(frozen=True, kw_only=True)
class StartProcess(Step):
    spec: ProcessSpec


@dataclass(frozen=True, kw_only=True)
class StartTimer(Step):
    period_s: float
    steps: tuple[Step, ...]
    cancel_on_shutdown: bool = True


@dataclass(frozen=True, kw_only=True)
class LogMessage(Step):
    message: str


@dataclass(frozen=True, kw_only=True)
class RequestShutdown(Step):
    reason: str


@dataclass(frozen=True, kw_only=True)
class Skipped(Step):
    """An entity whose `if:`/`unless:` was false: nothing runs, `--print` shows it."""

    what: str
    condition: str


@dataclass(frozen=True, kw_only=True)
class SignalProcesses(Step):
    """EmitEvent(SignalProcess / ShutdownProcess): signal the targets' groups (None: stop them, escalating)."""

    signal: int | None
    targets: tuple[TargetRef, ...]


@dataclass(frozen=True, kw_only=True)
class Unknown(Step):
    """What `--print` cannot know before run time: a handler's or timer's actions that fail if evaluated now."""

    what: str
    why: str


@dataclass(frozen=True)
class EventInfo:
    """What happened, for a callable handler: the process, its pid, exit code or output line."""

    name: str
    pid: int | None = None
    exit_code: int | None = None
    text: str | None = None
    stream: str | None = None


@dataclass(frozen=True)
class Handler:
    event: Literal["exit", "start", "shutdown", "io"]
    targets: tuple[TargetRef, ...]  # empty: any process
    steps: tuple[Step, ...]
    exit_code: int | None = None
    # A Python callable (launch's `on_exit=lambda event, context: …`): called when the event happens,
    # returns the steps of the actions it gave back (resolved then, not before).
    callback: Callable[[EventInfo], tuple[Step, ...]] | None = field(default=None, compare=False)
    streams: tuple[str, ...] = ()  # io: which of stdout / stderr
    describe_callback: str = ""
    once: bool = False  # handle_once: removed after it first fires

    def matches(self, name: str, exit_code: int | None = None) -> bool:
        if self.targets and name not in {t.name for t in self.targets}:
            return False
        return self.exit_code is None or exit_code == self.exit_code


@dataclass(frozen=True, kw_only=True)
class AddHandler(Step):
    handler: Handler


@dataclass(frozen=True)
class Argument:
    name: str
    value: str | None
    default: str | None
    description: str
    choices: tuple[str, ...] | None = None
    declared_in: str = ""
    default_substitutions: tuple[Any, ...] | None = None  # as written (--show-args describes them as launch does)


@dataclass
class Plan:
    source: str
    arguments: list[Argument]
    steps: tuple[Step, ...]
    processes: dict[str, ProcessSpec]
    warnings: list[str] = field(default_factory=list)
    description: Any = None  # what the live engine visits again when the launch runs
    launch_arguments: dict[str, str] = field(default_factory=dict)

    def uses_bus(self) -> set[str]:
        """Which bus probes ('topic', 'service') the plan's readiness conditions need."""
        kinds: set[str] = set()
        for step in walk(self.steps):
            if step.gate:
                kinds |= {w.kind for w in step.gate.waits if w.kind in ("topic", "service")}
        return kinds


def walk(steps: tuple[Step, ...]):
    """Every step, depth first, including those inside timers and handlers."""
    for step in steps:
        yield step
        if isinstance(step, StartTimer):
            yield from walk(step.steps)
        elif isinstance(step, AddHandler):
            yield from walk(step.handler.steps)
