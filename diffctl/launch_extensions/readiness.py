"""Readiness: visit actions only once processes have started, exited cleanly or printed a line, or a topic has a
publisher or a service answers (ros2 launch has no readiness; its users chain OnProcessExit handlers).

    - wait_for:                                 <wait_for exited="spawn_entity" topic="/robot_description"
        exited: spawn_entity                              timeout="30">
        topic: /robot_description                 <node …/>
        timeout: 30                             </wait_for>
        children: [{node: {…}}]

Conditions: `started`, `exited` (with code 0: another code fails the launch), `topic`, `service` (each a name or
a list of names), and `log` with `regex` (one process and pattern per wait_for; a line printed from when the
wait is reached counts). `timeout` (seconds) bounds the wait: running out of it fails the launch, naming what
was awaited. Python: `WaitFor([WaitFor.exited(spawn_entity), WaitFor.topic('/robot_description')],
actions=[node], timeout=30.0)`, processes given as their actions or by name.

The gated actions are visited with the locals the wait was reached with, as TimerAction's. Topic and service
conditions are answered by probes the launch's runner provides (`provide_probes`; `diffctl launch` gives the
bus's): launch itself knows processes, not the bus.
"""

from __future__ import annotations

import asyncio
import math
import re
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from diffctl.errors import LaunchError
from diffctl.launch.action import Action
from diffctl.launch.event import Event
from diffctl.launch.event_handler import BaseEventHandler
from diffctl.launch.events import Shutdown
from diffctl.launch.events.process import ProcessExited, ProcessIO, ProcessStarted
from diffctl.launch.frontend import Entity, Parser, expose_action
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.launch_description_entity import LaunchDescriptionEntity
from diffctl.launch.utilities import normalize_to_list_of_substitutions, perform_substitutions
from diffctl.launch_extensions import frontend_values, process_watch
from diffctl.launch_extensions.process_watch import ProcessRecord, process_names

KINDS = ("started", "exited", "log", "topic", "service")
PROCESS_KINDS = ("started", "exited", "log")
PROBES_KEY = "diffctl_readiness_probes"
FAILED_KEY = "diffctl_readiness_failed"  # what a wait that could not be met said (for a runner's exit code)
PROBE_PERIOD_S = 0.1

Probe = Callable[[str], bool]


def provide_probes(context: LaunchContext, probes: Mapping[str, Probe]) -> None:
    """Answer `topic` / `service` conditions with these (`{"topic": has_publisher, "service": answers}`); a probe
    may block, so it runs off the launch's loop, and one that raises counts as "not yet"."""
    context.extend_globals({PROBES_KEY: dict(probes)})


@dataclass(frozen=True)
class Condition:
    """One readiness condition: `kind` of `target` (a process action, or substitutions naming a process, a
    topic or a service); `regex` for `log`."""

    kind: str
    target: Any
    regex: str | None = None

    def describe(self) -> str:
        target = _describe_target(self.target)
        return f"log of {target} matching /{self.regex}/" if self.kind == "log" else f"{self.kind} {target}"


def _describe_target(target: Any) -> str:
    if isinstance(target, Action):
        names = process_names(target)
        if names:
            return min(names, key=len)
        description = getattr(target, "process_description", None)
        given = getattr(description, "name", None) or (getattr(description, "cmd", None) or [None])[0]
        return _describe_target(given) if given else type(target).__name__
    return "".join(getattr(s, "text", None) or s.describe() for s in target)


def _condition(kind: str, target: Any, regex: str | None = None) -> Condition:
    if kind not in KINDS:
        raise LaunchError(f"unknown readiness condition {kind!r}", hint="valid: " + ", ".join(KINDS))
    if not isinstance(target, Action):
        target = tuple(normalize_to_list_of_substitutions(target))
    if kind == "log":
        if regex is None:
            raise LaunchError("a log condition needs its regex")
        try:
            re.compile(regex)
        except re.error as e:
            raise LaunchError(f"log pattern {regex!r} is not a valid regular expression: {e}") from None
    return Condition(kind, target, regex)


class WaitFor(Action):
    """Visit `actions` once every condition holds (see the module's docstring)."""

    def __init__(
        self,
        conditions: Iterable[Condition],
        actions: Iterable[LaunchDescriptionEntity],
        *,
        timeout: float | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        self.conditions = list(conditions)
        if not self.conditions or not all(isinstance(c, Condition) for c in self.conditions):
            raise LaunchError(
                "WaitFor needs conditions: WaitFor.started/exited/log/topic/service(...)",
                hint="e.g. WaitFor([WaitFor.exited(spawn_entity)], actions=[node])",
            )
        self.actions = list(actions)
        for entity in self.actions:
            if not isinstance(entity, LaunchDescriptionEntity):
                raise LaunchError(f"WaitFor's actions must be launch entities, got {entity!r}")
        self.timeout_s = _timeout(timeout)
        self._future: asyncio.Future[None] | None = None

    # ---- the conditions, for launch files ----------------------------------------------------------------------

    @staticmethod
    def started(process: Any) -> Condition:
        return _condition("started", process)

    @staticmethod
    def exited(process: Any) -> Condition:
        return _condition("exited", process)

    @staticmethod
    def log(process: Any, regex: str) -> Condition:
        return _condition("log", process, regex)

    @staticmethod
    def topic(name: Any) -> Condition:
        return _condition("topic", name)

    @staticmethod
    def service(name: Any) -> Condition:
        return _condition("service", name)

    # ---- the frontends -----------------------------------------------------------------------------------------

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        _, kwargs = super().parse(entity, parser)
        conditions: list[Condition] = []
        for kind in ("started", "exited", "topic", "service"):
            value = entity.get_attr(kind, data_type=None, optional=True)
            for name in value if isinstance(value, list) else ([] if value is None else [value]):
                conditions.append(_condition(kind, parser.parse_substitution(str(name))))
        process = entity.get_attr("log", data_type=None, optional=True)
        regex = entity.get_attr("regex", optional=True)
        if (process is None) != (regex is None):
            raise LaunchError("wait_for's `log` and `regex` go together: log: PROCESS, regex: PATTERN")
        if process is not None:
            conditions.append(_condition("log", parser.parse_substitution(str(process)), regex))
        if not conditions:
            raise LaunchError("wait_for needs a condition", hint="valid: " + ", ".join(KINDS) + " (log with regex)")
        timeout = entity.get_attr("timeout", data_type=None, optional=True)
        kwargs["conditions"] = conditions
        kwargs["timeout"] = timeout
        kwargs["actions"] = [parser.parse_action(c) for c in frontend_values.action_entities(entity, "children") or ()]
        return cls, kwargs

    # ---- describing ------------------------------------------------------------------------------------------

    def describe(self) -> str:
        return f"WaitFor({', '.join(c.describe() for c in self.conditions)})"

    def __repr__(self) -> str:  # what launch's introspector (`--print`) shows of an action it does not know
        return self.describe()

    def describe_conditional_sub_entities(self) -> list[tuple[str, Iterable[LaunchDescriptionEntity]]]:
        what = " and ".join(c.describe() for c in self.conditions)
        if self.timeout_s is not None:
            what += f", within {self.timeout_s:g} s"
        return [(f"once {what}", self.actions)]

    # ---- running -----------------------------------------------------------------------------------------------

    def execute(self, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        watch = process_watch.install(context)
        waiter = _Waiter(self, context, watch)
        self._future = waiter.future
        state = waiter.state()
        if state is True:
            waiter.finish()
            return self.actions
        if isinstance(state, str):
            waiter.finish()
            raise _failed(context, f"{self.describe()}: {state}")
        waiter.start()
        return None

    def get_asyncio_future(self) -> asyncio.Future[None] | None:
        return self._future


def _failed(context: LaunchContext, message: str) -> LaunchError:
    """The error a wait that cannot be met raises (the launch fails), noted in the context's globals."""
    context.extend_globals({FAILED_KEY: message})
    return LaunchError(message)


def _timeout(value: Any) -> float | None:
    if value is None:
        return None
    try:
        t = float(value)
    except (TypeError, ValueError):
        raise LaunchError(f"wait_for timeout {value!r} is not a number of seconds") from None
    if not t > 0 or math.isinf(t):
        raise LaunchError(f"wait_for timeout {value!r} must be a positive number of seconds")
    return t


class ReadinessChanged(Event):
    """A bus probe answered, or a wait ran out of time (the launch's loop takes it from here)."""

    name = "diffctl.launch_extensions.readiness.ReadinessChanged"

    def __init__(self, waiter: _Waiter, why: str) -> None:
        super().__init__()
        self.waiter = waiter
        self.why = why


class _Watched:
    """One condition's state in one wait: met, or why it never will be."""

    def __init__(self, condition: Condition, context: LaunchContext) -> None:
        self.condition = condition
        self.kind = condition.kind
        self.action = condition.target if isinstance(condition.target, Action) else None
        self.name = None if self.action is not None else perform_substitutions(context, list(condition.target))
        self.regex = re.compile(condition.regex) if condition.regex else None
        self.met = False
        self.never: str | None = None
        self.pending_text = b""

    def label(self) -> str:
        if self.kind in ("topic", "service"):
            return f"{self.kind} {self.name}"
        who = self.name if self.name is not None else _describe_target(self.action)
        return f"log of {who} matching /{self.condition.regex}/" if self.kind == "log" else f"{self.kind} {who}"

    def concerns(self, action: Any, event_name: str | None) -> bool:
        if self.action is not None:
            return action is self.action
        return self.name in process_names(action, event_name)

    def from_history(self, record: ProcessRecord | None) -> None:
        if record is None or record.starts == 0:
            return
        if self.kind == "started":
            self.met = True
        elif self.kind == "exited" and not record.running:
            self._exited(record.returncode)
        elif self.kind == "log" and not record.running:
            self.never = f"{self._who()} ended before the wait began"

    def on_event(self, event: Any) -> None:
        if not isinstance(event, (ProcessStarted, ProcessExited, ProcessIO)):
            return
        if self.met or self.never or not self.concerns(event.action, event.process_name):
            return
        if isinstance(event, ProcessStarted) and self.kind == "started":
            self.met = True
        elif isinstance(event, ProcessExited):
            if self.kind == "exited":
                self._exited(event.returncode)
            elif self.kind == "log":
                self.never = f"{self._who()} ended without printing /{self.condition.regex}/"
        elif isinstance(event, ProcessIO) and self.kind == "log" and self.regex is not None:
            text = event.text if isinstance(event.text, bytes) else str(event.text).encode()
            *lines, self.pending_text = (self.pending_text + text).split(b"\n")
            if any(self.regex.search(line.decode("utf-8", "replace")) for line in lines):
                self.met = True

    def _exited(self, code: int | None) -> None:
        if code == 0:
            self.met = True
        else:
            self.never = f"{self._who()} exited with code {code}"

    def _who(self) -> str:
        return self.name if self.name is not None else _describe_target(self.action)


class _Waiter(BaseEventHandler):
    """One visit of a WaitFor: a handler of the events that may change its conditions."""

    def __init__(self, action: WaitFor, context: LaunchContext, watch: process_watch.ProcessWatch) -> None:
        super().__init__(matcher=self._concerns)
        self.action = action
        self.context = context
        self.future: asyncio.Future[None] = context.asyncio_loop.create_future()
        self.locals = dict(context.get_locals_as_dict())
        self.watched = [_Watched(c, context) for c in action.conditions]
        for w in self.watched:
            if w.kind in PROCESS_KINDS:
                w.from_history(watch.of_action(w.action) if w.action is not None else watch.of_name(w.name or ""))
        self.timed_out = False
        self.registered = False
        self.tasks: list[asyncio.Task[None]] = []
        self.started_at = context.asyncio_loop.time()

    def state(self) -> bool | str:
        """True when every condition holds, False while one may still come, or why one never will."""
        for w in self.watched:
            if w.never is not None:
                return f"cannot wait for {w.label()}: {w.never}"
            if not w.met:
                if self.timed_out:
                    return f"still waiting for {w.label()} after {self.action.timeout_s:g} s"
                return False
        return True

    def start(self) -> None:
        self.context.register_event_handler(self)
        self.registered = True
        loop = self.context.asyncio_loop
        bus = [w for w in self.watched if w.kind in ("topic", "service")]
        if bus:
            probes = self.context.get_locals_as_dict().get(PROBES_KEY) or {}
            missing = sorted({w.kind for w in bus} - set(probes))
            if missing:
                self.finish()
                raise _failed(
                    self.context,
                    f"{self.action.describe()}: nothing answers {' and '.join(missing)} conditions here "
                    "(diffctl launch provides the bus's probes: readiness.provide_probes)",
                )
            self.tasks.append(loop.create_task(self._poll(bus, probes)))
        if self.action.timeout_s is not None:
            self.tasks.append(loop.create_task(self._expire(self.action.timeout_s)))

    def finish(self) -> None:
        for task in self.tasks:
            task.cancel()
        if self.registered:
            self.registered = False
            self.context.unregister_event_handler(self)
        if not self.future.done():
            self.future.set_result(None)

    def _concerns(self, event: Any) -> bool:
        if isinstance(event, ReadinessChanged):
            return event.waiter is self
        if isinstance(event, Shutdown):
            return True
        return isinstance(event, (ProcessStarted, ProcessExited, ProcessIO)) and any(
            w.kind in PROCESS_KINDS and w.concerns(event.action, event.process_name) for w in self.watched
        )

    def handle(self, event: Any, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        super().handle(event, context)
        if isinstance(event, Shutdown):
            self.finish()  # nothing gated starts once the launch is going down
            return None
        if isinstance(event, ReadinessChanged) and event.why == "timeout":
            self.timed_out = True
        for w in self.watched:
            w.on_event(event)
        state = self.state()
        if state is False:
            return None
        self.finish()
        if isinstance(state, str):
            raise _failed(context, f"{self.action.describe()}: {state}")
        context.extend_locals(self.locals)
        return self.action.actions

    async def _poll(self, bus: list[_Watched], probes: Mapping[str, Probe]) -> None:
        loop = self.context.asyncio_loop
        while True:
            changed = False
            for w in bus:
                if w.met:
                    continue
                try:
                    w.met = bool(await loop.run_in_executor(None, probes[w.kind], w.name))
                except Exception:
                    w.met = False  # a probe that fails is "not yet"; the timeout bounds the wait
                changed |= w.met
            if changed:
                await self.context.emit_event(ReadinessChanged(self, "probe"))
            if all(w.met for w in bus):
                return
            await asyncio.sleep(PROBE_PERIOD_S)

    async def _expire(self, timeout_s: float) -> None:
        await asyncio.sleep(timeout_s)
        await self.context.emit_event(ReadinessChanged(self, "timeout"))

    @property
    def handler_description(self) -> str:
        return f"<{self.action.describe()}>"


expose_action("wait_for")(WaitFor)
