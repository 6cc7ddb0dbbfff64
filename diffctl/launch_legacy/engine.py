"""The launch engine, as ros2/launch's LaunchService: entities visited when they are reached, events in a queue.

`visit(entity)` evaluates the entity's condition, calls its `execute(context)` and visits what that returns,
depth first, at once (a whole included file inside one visit). Event handlers live in the context, the newest
first; every event is offered to a snapshot of them and every matching handler runs, its entities visited
then, with the launch configurations, environment and files of that moment. Timers and handlers are therefore
evaluated when they fire, not when the file is read.

What an action does to the world goes through the engine's `services`, which are one of two:
- the supervisor (live): processes start after the visit that asked for them completes (so a visit that
  fails starts nothing), readiness gates hold actions back, timers run on the supervisor's clock;
- a `PlanRecorder` (`--print`, tests): the effects are recorded as plan steps, a handler's or timer's actions
  are previewed in a copy of the context, and what cannot be known before run time is said so.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable, Iterable
from dataclasses import replace
from pathlib import Path
from typing import Any, Protocol

from diffctl.errors import LaunchError, suggest
from diffctl.launch_legacy import events
from diffctl.launch_legacy.context import LaunchContext
from diffctl.launch_legacy.plan import (
    PROCESS_WAIT_KINDS,
    AddHandler,
    Argument,
    Gate,
    Handler,
    ProcessSpec,
    Skipped,
    StartProcess,
    Step,
    TargetRef,
    Unknown,
    Wait,
    Where,
)
from diffctl.launch_legacy.substitutions import perform


class Services(Protocol):
    """What the engine asks of the world: the supervisor, or a recorder of the plan."""

    def effect(self, step: Step) -> None: ...

    def gated(self, gate: Gate, visit: Callable[[], None], label: str) -> None: ...

    def after(self, delay_s: float, callback: Callable[[], None], kind: str) -> Any: ...


class Engine:
    def __init__(
        self,
        arguments: dict[str, str],
        source: str | None,
        services: Services,
        *,
        dry: bool = False,
        env: dict[str, str] | None = None,
        output_default: str = "screen",
        process_names: str = "diffctl",
    ) -> None:
        self.context = LaunchContext(arguments, source, env, engine=self)
        self.process_names = process_names
        self.services = services
        self.dry = dry
        self.output_default = output_default
        self.processes: dict[str, ProcessSpec] = {}
        self.origin_names: dict[int, str] = {}
        self.process_actions: dict[str, Any] = {}
        self.arguments: list[Argument] = []
        self.warnings: list[str] = []
        self.queue: deque[Any] = deque()
        self._processing = False
        self._buffer: list[Step] | None = None  # live: effects held until the visit that made them completes
        self._declared: list[list[str]] = []
        self._current: tuple[Where, str] = (Where(), "")
        self._refs: list[tuple[TargetRef, bool, Where, str]] = []
        self._skipped = False
        self.io_seq: dict[str, int] = {}  # process name → when its output handler was registered (ROS's order)
        self._seq = 0
        self.include_stack: list[str] = [source] if source else []  # the files being visited, for cycles
        self.errors: list[str] = []  # exceptions while handling events: ROS's "Caught exception in launch"

    # ---- visiting ----------------------------------------------------------------------------------------------

    def run_description(self, description: Any, hold: list[Step] | None = None) -> None:
        """The initial visit (an IncludeLaunchDescription event in ROS); its processes start when it is done,
        or, with `hold`, are put there for the caller to start (a failing visit starts nothing)."""
        from diffctl.launch_legacy.resolver import declared_names

        self._declared.append(declared_names(description))
        try:
            if hold is None or self.dry:
                self.visit_and_flush(lambda: self.visit_all(description.entities))
            else:
                self._buffer = hold
                try:
                    self.visit_all(description.entities)
                    self._link()
                finally:
                    self._buffer = None
        finally:
            self._declared.pop()

    def visit_all(self, entities: Iterable[Any]) -> None:
        for entity in entities:
            self.visit(entity)

    def visit(self, action: Any) -> None:
        ctx = self.context
        try:
            if action.condition is not None and not action.condition.evaluate(ctx):
                self._skipped = True
                if self.dry:
                    self.services.effect(
                        Skipped(what=action.label(), condition=action.condition.describe(), where=str(action.where))
                    )
                return
            gate = self._gate(action)
        except LaunchError as e:
            raise action.where.attach(e, action.label()) from None
        if gate is None:
            self._visit_now(action)
            return
        saved = ctx.get_locals_as_dict()

        def later() -> None:
            with ctx.frame(saved):
                self._visit_now(action)

        from diffctl.launch_legacy.status import _static_name

        label = _static_name(action) or action.label()
        self.services.gated(gate, later if not self.dry else (lambda: self._visit_now(action)), label)

    def _visit_now(self, action: Any) -> None:
        outer, self._current = self._current, (action.where, action.label())
        try:
            entities = action.execute(self.context)
            # As Action.visit: whether an ExecutionComplete is wanted is decided now, by the handlers registered
            # now; it is emitted now, or when the action's work ends (a process's last exit, a timer firing).
            wanted = self._would_handle_completion(action)
            if getattr(action, "completes_later", False):
                action._completion_wanted = wanted
            elif wanted:
                self.emit(events.ExecutionComplete(action=action))
            if entities:
                self.visit_all(entities)
        except LaunchError as e:
            raise action.where.attach(e, action.label()) from None
        finally:
            self._current = outer

    def effect(self, step: Step) -> None:
        """Something for the world to do: start a process, log, shut down, signal."""
        if not step.where:
            step = replace(step, where=str(self._current[0]))
        if self._buffer is not None:
            self._buffer.append(step)
        else:
            self.services.effect(step)

    def visit_and_flush(self, visit: Callable[[], None]) -> None:
        if self.dry or self._buffer is not None:
            visit()
            return
        self._buffer = []
        try:
            visit()
            self._link()
        except BaseException:
            self._buffer = None
            raise
        steps, self._buffer = self._buffer, None
        for step in steps:
            self.services.effect(step)

    def amend_start(self, name: str, change: Callable[[tuple[str, ...]], tuple[str, ...]]) -> bool:
        """Change the command of a process this visit starts and that has not started yet (False: too late)."""
        steps = self._buffer if self._buffer is not None else getattr(self.services, "steps", None)
        for i, step in enumerate(steps or []):
            if isinstance(step, StartProcess) and step.spec.name == name:
                spec = replace(step.spec, argv=change(step.spec.argv))
                steps[i] = replace(step, spec=spec)  # type: ignore[index]
                self.processes[name] = spec
                return True
        return False

    def defer(self, function: Callable[[], None]) -> None:
        """Run after the current visit and the events before it (TimerAction's coroutine)."""
        self.queue.append(function)

    # ---- events ------------------------------------------------------------------------------------------------

    def register(self, handler: Any, *, append: bool = False) -> None:
        handler.launch_file = self.context.launch_file
        self._seq += 1
        handler.seq = self._seq
        if self.dry:
            self.services.effect(AddHandler(handler=self.preview_handler(handler)))
            return
        if append:
            self.context.handlers.append(handler)
        else:
            self.context.handlers.appendleft(handler)

    def emit(self, event: Any) -> None:
        self.queue.append(event)

    def process_events(self) -> None:
        """Handle queued events, oldest first, each by every matching handler, newest registered first."""
        if self._processing or self.dry:
            return
        self._processing = True
        try:
            while self.queue:
                item = self.queue.popleft()
                try:
                    if callable(item) and not isinstance(item, events.Event):
                        self.visit_and_flush(item)
                    else:
                        self._handle(item)
                except LaunchError as e:
                    self.failed(e)
        finally:
            self._processing = False

    def _handle(self, event: Any) -> None:
        ctx = self.context
        # A process's output is printed by its own handler, registered when it started (`print_seq`).
        print_seq = getattr(event, "print_seq", None)
        for handler in tuple(ctx.handlers):
            if print_seq is not None and handler.seq < print_seq:
                self._print(event)
                print_seq = None
            if not handler.matches(event):
                continue
            handler.fired = True
            frame = {"event": event, "current_launch_file_path": handler.launch_file}

            def run(handler: Any = handler, frame: dict[str, Any] = frame) -> None:
                with ctx.frame(frame):
                    entities = handler.handle(event, ctx)
                    if entities:
                        self.visit_all(entities)

            self.visit_and_flush(run)
        if print_seq is not None:
            self._print(event)
        if isinstance(event, events.IncludeLaunchDescription):  # ROS's own OnIncludeLaunchDescription, the oldest
            with ctx.frame({"event": event}):
                self.visit_and_flush(lambda: self.visit_all([event.launch_description]))
        if isinstance(event, events.TimerEvent):
            action = event.timer_action

            def fire() -> None:
                with ctx.frame(dict(event.locals)):
                    self.visit_all(action.actions)
                self.completed(action)

            self.visit_and_flush(fire)

    def _print(self, event: Any) -> None:
        text = event.text.decode("utf-8", errors="replace")
        self.services.print_io(
            event.name, "stdout" if event.fd == 1 else "stderr", text[:-1] if text.endswith("\n") else text
        )

    def lifecycle(self) -> Any:
        """The bus side of managed nodes, when the launch was given one (None in a dry run)."""
        get = getattr(self.services, "lifecycle_services", None)
        if self.dry or get is None:
            return None
        try:
            return get()
        except Exception as e:  # the bus side failed to come up: a launch error, not a crash
            raise LaunchError(f"lifecycle nodes need the bus, which failed: {type(e).__name__}: {e}") from None

    def post_event(self, event: Any) -> None:
        """From another thread (a bus callback): emit `event` on the launch's own thread."""
        self.services.post(lambda: self.emit(event))  # type: ignore[attr-defined]

    def post_log(self, level: str, message: str) -> None:
        self.services.post(lambda: self.services.log(level, message))  # type: ignore[attr-defined]

    def failed(self, error: LaunchError) -> None:
        """An exception while handling an event: logged, and the launch shuts down with code 1 (as ROS)."""
        message = str(error)
        self.errors.append(message)
        request = getattr(self.services, "event_failed", None)
        if request is not None:
            request(message)
        else:
            raise error

    def _would_handle_completion(self, action: Any) -> bool:
        if self.dry or not self.context.handlers:
            return False
        event = events.ExecutionComplete(action=action)
        return any(h.matches(event) for h in self.context.handlers)

    def completed(self, action: Any) -> None:
        """The work of an action that completes later is done: its ExecutionComplete, if it was wanted."""
        if getattr(action, "_completion_wanted", False):
            action._completion_wanted = False
            self.emit(events.ExecutionComplete(action=action))

    def process_event(self, kind: str, name: str, **fields: Any) -> Any:
        """A process event (started / exited / io) for the process called `name`."""
        spec = self.processes.get(name)
        common = {
            "action": self.process_actions.get(name),
            "name": name,
            "cmd": list(spec.argv) if spec else [],
            "cwd": spec.cwd if spec else None,
            "env": dict(self.context.env),
        }
        cls = {"start": events.ProcessStarted, "exit": events.ProcessExited, "io": events.ProcessIO}[kind]
        return cls(**common, **fields)

    # ---- previews (--print) ------------------------------------------------------------------------------------

    def preview(self, entities: Iterable[Any], frame: dict[str, Any] | None = None) -> tuple[Step, ...]:
        """What `entities` would do if visited now, in a copy of the context (for `--print`)."""
        recorder = self.services
        assert isinstance(recorder, PlanRecorder)
        saved = self.context
        self.context = saved.snapshot()
        if frame:
            self.context.extend_locals(frame)
        recorder.open()
        try:
            self.visit_all(entities)
        except LaunchError as e:
            self.services.effect(Unknown(what="actions", why=str(e)))
        finally:
            self.context = saved
        return recorder.close()

    def preview_handler(self, handler: Any) -> Handler:
        refs = tuple(self.ref(t) for t in handler.name_targets())
        entities = handler.entities or []
        steps = self.preview(entities, {"event": None}) if entities else ()
        callback = handler.callable
        return Handler(
            handler.kind,  # type: ignore[arg-type]
            refs,
            steps,
            handler.exit_code,
            callback=callback,
            streams=handler.streams,
            describe_callback=handler.describe_callable(),
            once=handler.handle_once,
        )

    # ---- bookkeeping used by actions ---------------------------------------------------------------------------

    def add_process(self, action: Any, name: str, **fields: Any) -> ProcessSpec:
        if not name:
            raise LaunchError("a process needs a name")
        unique = name
        n = 2
        if self.process_names == "ros":
            # ExecuteProcess's names: `-N` from one counter for every process (talker-1, talker-2, rsp-3 …)
            unique = f"{name}-{len(self.processes) + 1}"
        while unique in self.processes:
            unique = f"{name}-{n}"
            n += 1
        self.origin_names[id(action)] = unique
        action._process_name = unique
        spec = ProcessSpec(name=unique, where=str(action.where), origin=id(action), **fields)
        self.processes[unique] = spec
        self.process_actions[unique] = action
        self._seq += 1
        self.io_seq[unique] = self._seq
        return spec

    def ref(self, target: Any, *, must_exist: bool = False) -> TargetRef:
        """A process named by a handler or readiness condition: an action object, or its name."""
        from diffctl.launch_legacy.actions import Action

        if isinstance(target, TargetRef):
            ref = target
        elif isinstance(target, Action):
            ref = TargetRef(origin=id(target), label=target.label(), name=self.origin_names.get(id(target)))
        else:
            name = perform(target, self.context)
            ref = TargetRef(name=name, label=name)
        self._refs.append((ref, must_exist, *self._current))
        return ref

    def name_of(self, ref: TargetRef) -> str | None:
        if ref.name is None and ref.origin is not None:
            ref.name = self.origin_names.get(ref.origin)
        return ref.name

    def declare(self, argument: Argument) -> None:
        if all(a.name != argument.name for a in self.arguments):
            self.arguments.append(argument)

    def missing_argument(self, name: str) -> None:
        declared = self._declared[-1] if self._declared else []
        raise LaunchError(
            f"missing required launch argument {name!r}",
            hint=f"pass {name}:=VALUE; declared arguments: " + ", ".join(declared),
        )

    def include(self, path: Path) -> list[Any]:
        from diffctl.launch_legacy.loader import load
        from diffctl.launch_legacy.resolver import declared_names

        description = load(path)
        self._declared.append(declared_names(description))
        self.include_stack.append(str(path))
        return [*description.entities, _PopDeclared(self)]

    def _gate(self, action: Any) -> Gate | None:
        if not action.wait_for:
            return None
        waits: list[Wait] = []
        for w in action.wait_for:
            if w.kind in PROCESS_WAIT_KINDS:
                waits.append(Wait(w.kind, self.ref(w.target, must_exist=True), w.pattern))
            else:
                name = perform(w.target, self.context)
                if not name.startswith("/"):
                    name = self.context.namespace.rstrip("/") + "/" + name
                waits.append(Wait(w.kind, name))
        return Gate(tuple(waits), action.wait_timeout)

    def _link(self, final: bool = False) -> None:
        """Names for the processes handlers and gates refer to; in a dry run, unknown names are errors."""
        names = sorted(self.processes)
        refs, self._refs = self._refs, []
        for ref, must_exist, where, entity in refs:
            if ref.origin is not None:
                if self.name_of(ref) is None:
                    if must_exist and final:
                        raise where.attach(
                            LaunchError(
                                f"wait_for names {ref.label}, which this launch never starts",
                                hint="is it skipped by its condition?",
                            ),
                            entity,
                        )
                    self._refs.append((ref, must_exist, where, entity))
                continue
            if not final or ref.name in self.processes:
                continue
            message = f"unknown process {ref.name!r}{suggest(ref.name or '', names)}"
            if must_exist or not self._skipped:
                raise where.attach(LaunchError(message, hint="processes: " + (", ".join(names) or "none")), entity)
            self.warnings.append(f"{where}: {message} (its handler will never run)")


class _PopDeclared:
    """Visited after an included file's entities: its declared names stop being the ones errors list."""

    condition = None
    where = Where()
    completes_later = True

    def __init__(self, engine: Engine) -> None:
        self.engine = engine
        self.wait_for: list[Any] = []

    def label(self) -> str:
        return "end of include"

    def execute(self, context: LaunchContext) -> None:
        if self.engine._declared:
            self.engine._declared.pop()
        if self.engine.include_stack:
            self.engine.include_stack.pop()


class PlanRecorder:
    """Services of a dry run: effects become plan steps (nested while a handler or timer is previewed)."""

    def __init__(self) -> None:
        self.stack: list[list[Step]] = [[]]

    @property
    def steps(self) -> list[Step]:
        return self.stack[0]

    def open(self) -> None:
        self.stack.append([])

    def close(self) -> tuple[Step, ...]:
        return tuple(self.stack.pop())

    def effect(self, step: Step) -> None:
        self.stack[-1].append(step)

    def gated(self, gate: Gate, visit: Callable[[], None], label: str) -> None:
        self.open()
        visit()
        for step in self.close():
            self.effect(step.with_gate(gate))

    def after(self, delay_s: float, callback: Callable[[], None], kind: str) -> None:
        return None
