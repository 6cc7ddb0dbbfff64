"""The supervisor: the launch engine's services (processes, timers, readiness gates) and its event source.

It is a state machine driven from outside: `start()`, then `on_exit(pid, code)`, `on_line(name, …)`,
`on_signal(sig)` and `tick()` as things happen, until `done`. The engine (engine.py) visits the launch
description when `prepare()`/`start()` is called and the entities of handlers and timers when their events
(which the supervisor emits: process started / exited / output, shutdown, timer) are processed; what they
do comes back here as effects (start a process, log, shut down, signal). The clock and the process spawner
are injected, so unit tests run it with fakes; loop.py drives it with real processes, pipes and signals.

Shutdown (Ctrl-C, SIGTERM, SIGHUP, a required process exiting, a `shutdown` action, or nothing left to
do) first offers a Shutdown event to the handlers (processes they start run only after a `shutdown` action or
a required process's exit, as in Jazzy), then sends SIGINT to every process group in reverse start order,
SIGTERM after its `sigterm_timeout`, SIGKILL after its `sigkill_timeout`, each step logged; a second Ctrl-C
sends SIGKILL at once.
"""

from __future__ import annotations

import heapq
import itertools
import os
import re
import signal
import tempfile
from collections import deque
from collections.abc import Callable
from pathlib import Path
from typing import Any

from diffctl.errors import LaunchError
from diffctl.launch_legacy import commandline, events
from diffctl.launch_legacy.engine import Engine
from diffctl.launch_legacy.environment import child_env, with_tool_path
from diffctl.launch_legacy.output import Output
from diffctl.launch_legacy.plan import (
    Gate,
    LogMessage,
    Plan,
    ProcessSpec,
    RequestShutdown,
    SignalProcesses,
    StartProcess,
    Step,
    TargetRef,
    Wait,
    walk,
)
from diffctl.launch_legacy.process_state import (
    Child,
    Clock,
    Pending,
    ProcessState,
    Spawner,
    SystemClock,
    Timer,
    describe_exit,
    died,
    wait_state,
)
from diffctl.launch_legacy.readiness import ProbePoller
from diffctl.launch_legacy.status import ProcessRow, StatusView, awaited, process_rows

STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)


class Supervisor:
    def __init__(
        self,
        plan: Plan,
        *,
        spawner: Spawner,
        output: Output | None,
        clock: Clock | None = None,
        log_dir: Path | None = None,
        poller: ProbePoller | None = None,
        env: dict[str, str] | None = None,
        output_default: str = "screen",
        exit_code_mode: str = "diffctl",
        lifecycle: Callable[[Callable[[], None]], Any] | None = None,
        signal_scope: str = "group",
        process_names: str = "diffctl",
        real_environ: bool = False,
    ) -> None:
        """lifecycle: makes the bus side of LifecycleNode (given a thread-safe `post`), on first use."""
        self.plan = plan
        self.exit_code_mode = exit_code_mode
        self.spawner = spawner
        self.output: Output = output  # type: ignore[assignment]  # the CLI gives it after prepare()
        self.clock = clock or SystemClock()
        self.params_dir = (log_dir / "params") if log_dir else Path(tempfile.gettempdir()) / f"diffctl-{os.getpid()}"
        self.poller = poller
        self.base_env = with_tool_path(dict(os.environ if env is None else env))  # as default_child_env
        # Known ahead from a dry run (--print's walk), when there was one: shown as "not started" until they are.
        self.states = {name: ProcessState(spec) for name, spec in plan.processes.items()}
        self.pid_names: dict[int, str] = {}
        self.started_at: dict[int, float] = {}  # pgid → when that start of the process began
        self.signal_scope = signal_scope
        self.engine = Engine(
            dict(plan.launch_arguments),
            plan.source,
            self,
            output_default=output_default,
            process_names=process_names,
            env=os.environ if real_environ else None,  # type: ignore[arg-type]
        )
        self._held: list[Step] | None = None
        self._inbox: deque[Callable[[], None]] = deque()  # work posted from other threads (bus callbacks)
        self._make_lifecycle = lifecycle
        self._lifecycle: Any = None
        self.notify: Callable[[], None] = lambda: None  # wakes the event loop (set by loop.py)
        self.start_order: list[str] = []
        self.pending: list[Pending] = []
        self.failures: list[str] = []  # why the launch failed: required process, readiness, …
        self.failed_processes: list[str] = []
        self.shutting_down = False
        self.natural_end = False
        self.done = False
        self.exit_code = 0
        self.started_all_at: float | None = None
        self._timers: list[tuple[float, int, Timer]] = []
        self._seq = itertools.count()
        self._t0 = 0.0
        self._shutdown_at: float | None = None
        self._patterns: dict[str, list[tuple[str, re.Pattern[str]]]] = {}
        self._watched: set[tuple[str, str]] = set()
        for step in walk(plan.steps):
            if step.gate:
                self._watch_patterns(step.gate)

    # ---- driving -----------------------------------------------------------------------------------------------

    def now(self) -> float:
        return self.clock.monotonic()

    def prepare(self) -> None:
        """Visit the launch description (errors raise, naming file and line); nothing starts before start()."""
        if self._held is not None:
            return
        self._held = []
        self.engine.run_description(self.plan.description, hold=self._held)

    def may_start_components(self, is_component: Callable[[tuple[str, ...]], bool]) -> bool:
        """Whether a process the first visit starts, or a handler or timer may start later, is a component."""
        if self.engine.context.handlers or self.engine.queue:
            return True
        return any(isinstance(s, StartProcess) and is_component(s.spec.argv) for s in self._held or ())

    def bus_waits(self) -> set[str]:
        """The bus probes ('topic', 'service') readiness conditions anywhere in the description need."""
        from diffctl.launch_legacy.actions import walk_entities

        kinds = {w.kind for a in walk_entities(self.plan.description) for w in a.wait_for}
        kinds |= {w.kind for p in self.pending for w in p.gate.waits}  # those of included files, visited now
        return kinds & {"topic", "service"}

    def use_poller(self, poller: ProbePoller) -> None:
        self.poller = poller
        for p in self.pending:
            for w in p.gate.waits:
                if w.kind in ("topic", "service"):
                    poller.want(w.kind, str(w.target))

    def start(self) -> None:
        self.prepare()
        self._t0 = self.now()  # "all N processes started in …" counts from here, the first visit being done
        declared = [a.name for a in self.engine.arguments]
        for name in self.plan.launch_arguments:
            if name not in declared and not self.plan.arguments:
                from diffctl.errors import suggest

                why = f"argument {name!r} is not declared by the launch file{suggest(name, declared)}"
                self.output.launcher("WARN", why)
        held, self._held = self._held or [], []
        for step in held:
            self.effect(step)
        self._after_event()

    # ---- the engine's services ---------------------------------------------------------------------------------

    def effect(self, step: Step) -> None:
        if isinstance(step, LogMessage):
            self.output.launcher("INFO", step.message, logger="launch.user")  # LogInfo's logger, as ROS's
        elif isinstance(step, StartProcess):
            self._start(step.spec)
        elif isinstance(step, RequestShutdown):
            self.shutdown(step.reason, by_action=True)
        elif isinstance(step, SignalProcesses):
            self._signal_processes(step)

    def gated(self, gate: Gate, visit: Callable[[], None], label: str) -> None:
        self._watch_patterns(gate)
        pending = Pending(_Deferred(label, visit), gate, self.now())
        if self._gate_state(gate)[0] is True:
            self._run_deferred(pending.step)
            return
        self.pending.append(pending)
        for w in gate.waits:
            if w.kind in ("topic", "service") and self.poller is not None:
                self.poller.want(w.kind, str(w.target))

    def after(self, delay_s: float, callback: Callable[[], None], kind: str) -> Timer:
        return self._after(delay_s, callback, kind)

    def post(self, work: Callable[[], None]) -> None:
        """Thread-safe: run `work` on the launch's thread (deque appends are atomic)."""
        self._inbox.append(work)
        self.notify()

    def log(self, level: str, message: str) -> None:
        self.output.launcher(level, message)

    def lifecycle_services(self) -> Any:
        if self._lifecycle is None and self._make_lifecycle is not None:
            self._lifecycle = self._make_lifecycle(self.post)
        return self._lifecycle

    def close(self) -> None:
        if self._lifecycle is not None and hasattr(self._lifecycle, "close"):
            self._lifecycle.close()

    def event_failed(self, message: str) -> None:
        """An exception while handling an event, as ros2/launch: logged, the launch shuts down, exit code 1."""
        self.failures.append(message)
        self.output.launcher("ERROR", f"Caught exception in launch: {message}")
        self.shutdown(message)

    def _run_deferred(self, deferred: _Deferred) -> None:
        try:
            self.engine.visit_and_flush(deferred.visit)
        except LaunchError as e:
            self.event_failed(str(e))

    def _watch_patterns(self, gate: Gate) -> None:
        for w in gate.waits:
            if w.kind == "log" and isinstance(w.target, TargetRef) and w.pattern:
                name = self.engine.name_of(w.target) or w.target.name
                if name and (w.pattern, name) not in self._watched:
                    self._watched.add((w.pattern, name))
                    self._patterns.setdefault(name, []).append((w.pattern, re.compile(w.pattern)))

    def on_exit(self, pid: int, code: int) -> None:
        name = self.pid_names.pop(pid, None)
        if name is None:
            return
        st = self.states[name]
        child, st.child = st.child, None
        st.exit_code = code
        if child is not None and self.spawner.group_alive(child):
            st.lingering = child
        elif child is not None:
            self.spawner.forget(child)
        self._process_exited(st, code, pid, self._ran(child))
        if st.lingering is not child and child is not None:
            self.started_at.pop(child.pgid, None)
        self._after_event()

    def on_line(self, name: str, stream: str, text: str) -> None:
        st = self.states.get(name)
        if st is None:
            return
        st.tail.append(text)
        if self._io_handlers:
            # The process's own output handler is registered when it starts: handlers registered after it
            # run before its line is printed, older ones after (ros2/launch's order, newest first).
            pid = st.child.pid if st.child else None
            event = self.engine.process_event(
                "io", name, pid=pid, text=(text + "\n").encode(), fd=1 if stream == "stdout" else 2
            )
            event.print_seq = self.engine.io_seq.get(name, 0)
            self.engine.emit(event)
            self._after_event()
        else:
            self.print_io(name, stream, text)
        for pattern, compiled in self._patterns.get(name, ()):
            if pattern not in st.seen_patterns and compiled.search(text):
                st.seen_patterns.add(pattern)
                self._after_event()

    def print_io(self, name: str, stream: str, text: str) -> None:
        st = self.states.get(name)
        if st is None:
            return
        screen = st.spec.output in ("screen", "both") or stream == "stderr"
        self.output.process_line(name, stream, text, screen=screen)

    def on_signal(self, sig: int) -> None:
        if sig == signal.SIGUSR1:
            self.show_status()
        elif sig in STOP_SIGNALS:
            name = signal.Signals(sig).name
            if not self.shutting_down:
                self.shutdown(
                    "ctrl-c (SIGINT)" if sig == signal.SIGINT else f"{name} received",
                    due_to_sigint=sig == signal.SIGINT,
                )
            else:
                self._kill_all(f"{name} again")
            self._after_event()

    def tick(self) -> None:
        while self._inbox:
            self._inbox.popleft()()
        now = self.now()
        while self._timers and self._timers[0][0] <= now:
            _, _, timer = heapq.heappop(self._timers)
            if not timer.cancelled:
                timer.callback()
        for st in self.states.values():
            if st.lingering is not None and not self.spawner.group_alive(st.lingering):
                gone, st.lingering = st.lingering, None
                self.spawner.forget(gone)
                self.output.launcher("INFO", f"[{st.spec.name}] the rest of its process group is gone{self._ran(gone)}")
                self.started_at.pop(gone.pgid, None)
        self._after_event()

    def next_deadline(self) -> float | None:
        """When `tick()` must run next (None: only when something happens)."""
        while self._timers and self._timers[0][2].cancelled:
            heapq.heappop(self._timers)
        deadlines = [self._timers[0][0]] if self._timers else []
        now = self.now()
        if self.pending:
            deadlines.append(now + 0.1)  # bus probes answer asynchronously; gate timeouts
        if any(st.lingering for st in self.states.values()):
            deadlines.append(now + 0.05)
        return min(deadlines) if deadlines else None

    # ---- steps -------------------------------------------------------------------------------------------------

    def _signal_processes(self, step: SignalProcesses) -> None:
        for ref in step.targets:
            st = self.states.get(self.engine.name_of(ref) or ref.name or "")
            if st is None or not st.alive:
                self.output.launcher("WARN", f"cannot signal [{ref}]: it is not running")
            elif step.signal is None:
                self._stop(st, signal.SIGINT)
            else:
                self.output.launcher("INFO", f"sending {signal.Signals(step.signal).name} to [{st.spec.name}]")
                self._send(st.child or st.lingering, step.signal)  # type: ignore[arg-type]

    def _after(self, delay_s: float, callback: Callable[[], None], kind: str) -> Timer:
        timer = Timer(callback, kind)
        heapq.heappush(self._timers, (self.now() + delay_s, next(self._seq), timer))
        return timer

    # ---- processes ---------------------------------------------------------------------------------------------

    def _env(self, spec: ProcessSpec) -> dict[str, str]:
        env = {} if spec.env_replace else dict(self.base_env)
        for key, value in spec.env.items():
            if value is None:
                env.pop(key, None)
            else:
                env[key] = value
        return child_env(env)

    def _start(self, spec: ProcessSpec) -> None:
        st = self.states.get(spec.name)
        if st is None:
            st = self.states[spec.name] = ProcessState(spec)
        elif spec is not st.spec and not st.alive:
            st.spec = spec  # evaluated now, not as a dry run saw it
        if spec.name not in self.plan.processes or self.plan.processes[spec.name] is not spec:
            self.plan.processes[spec.name] = spec
        if st.alive:
            self.output.launcher(
                "WARN",
                f"[{spec.name}] is already running (pid {st.child.pid if st.child else '?'}); "
                "not starting a second one",
            )
            return
        try:
            argv = commandline.argv(spec, self.params_dir, write=True)
            child = self.spawner.spawn(spec.name, argv, self._env(spec), spec.cwd, spec.interactive)
        except OSError as e:
            self.output.launcher("ERROR", f"[{spec.name}] could not start: {e.strerror or e}")
            st.tail.append(f"could not start: {e.strerror or e}")
            st.exit_code = 127
            self._process_exited(st, 127, None, "")
            return
        st.child = child
        st.state = "running"
        st.starts += 1
        st.started_at = self.started_at[child.pgid] = self.now()
        self.pid_names[child.pid] = spec.name
        if spec.name not in self.start_order:
            self.start_order.append(spec.name)
        if self.started_all_at is None:
            self.output.live(self._live_text())  # this one is no longer awaited
        self.output.launcher("INFO", f"[{spec.name}] started (pid {child.pid})")
        self.engine.emit(self.engine.process_event("start", spec.name, pid=child.pid))

    def _process_exited(self, st: ProcessState, code: int, pid: int | None, ran: str) -> None:
        name = st.spec.name
        where = f"pid {pid}{ran}" if pid else "never started"
        event = self.engine.process_event("exit", name, pid=pid, returncode=code)
        if self.shutting_down:
            st.state = "stopped"
            self.output.launcher("INFO", f"[{name}] stopped ({describe_exit(code)}, {where})")
            if st.lingering is not None:
                # The leader went on SIGINT, the rest stayed: a non-interactive shell's background job ignores
                # SIGINT, so waiting out sigterm_timeout for it would only delay the inevitable.
                self.output.launcher("INFO", f"[{name}] left processes in its group; sending them SIGTERM")
                self._stop(st, signal.SIGTERM, quiet=True)
            self.engine.emit(event)  # handlers still hear of it, as in ros2/launch (nothing new starts)
            self._complete(name)
            return
        if code == 0:
            st.state = "exited"
            self.output.launcher("INFO", f"[{name}] finished cleanly ({where})")
        else:
            st.state = "failed"
            last = f": {st.tail[-1]}" if st.tail else ""
            self.output.launcher("ERROR", f"[{name}] {died(code)} ({where}){last}")
        self.engine.emit(event)
        if st.spec.required:
            why = f"required process {name!r} {'finished' if code == 0 else died(code)}"
            if code != 0:
                self.failures.append(why + (f" (last output: {st.tail[-1]!r})" if st.tail else ""))
            self._complete(name)
            # on_exit=Shutdown(): the event's reason is that action's, and handlers' processes start, as in ROS
            self.shutdown(why, by_action=True, event_reason="reason not given")
        elif st.respawns_left:
            st.restarts += 1
            st.state = "respawning"
            limit = st.spec.respawn_max_retries
            self.output.launcher(
                "INFO",
                f"[{name}] respawning in {st.spec.respawn_delay_s:g} s "
                f"(restart {st.restarts}{'' if limit < 0 else f' of {limit}'})",
            )
            self._after(st.spec.respawn_delay_s, lambda: self._start(st.spec), "respawn")
        else:
            if code != 0:
                self.failed_processes.append(f"{name} ({describe_exit(code)})")
            self._complete(name)
        if st.lingering is not None and not self.shutting_down:
            # What is left (a shell's background job) may well ignore SIGINT, as jobs of a non-interactive shell
            # do: waiting out sigterm_timeout for it would only delay the inevitable.
            self.output.launcher("WARN", f"[{name}] exited but left processes in its group; sending them SIGTERM")
            self._stop(st, signal.SIGTERM, quiet=True)

    def _ran(self, child: Child | None) -> str:
        """', ran 3.2 s': since the start that made this group (kept per group, so a respawn, which starts the
        count of its own group again, leaves the figure of the one before it intact)."""
        started = self.started_at.get(child.pgid) if child is not None else None
        return f", ran {self.now() - started:.1f} s" if started is not None else ""

    @property
    def _io_handlers(self) -> bool:
        return any(getattr(h, "kind", "") == "io" for h in self.engine.context.handlers)

    def _complete(self, name: str) -> None:
        action = self.engine.process_actions.get(name)
        if action is not None:
            self.engine.completed(action)

    # ---- readiness ---------------------------------------------------------------------------------------------

    def _wait_state(self, w: Wait) -> bool | str:
        """True when met, False while it may still be met, or the reason it never will be."""
        if isinstance(w.target, TargetRef) and (self.engine.name_of(w.target) or "") not in self.states:
            return False  # a process not reached yet (held back itself, or a handler or timer may start it)
        return wait_state(w, self.states, self.poller)

    def _gate_state(self, gate: Gate) -> tuple[bool | str, Wait | None]:
        for w in gate.waits:
            state = self._wait_state(w)
            if state is not True:
                return state, w
        return True, None

    def _check_gates(self) -> None:
        progress = True
        while progress and self.pending and not self.shutting_down:
            progress = False
            for p in list(self.pending):
                state, w = self._gate_state(p.gate)
                what = p.step.label
                if state is True:
                    self.pending.remove(p)
                    self._run_deferred(p.step)
                    progress = True
                elif isinstance(state, str):
                    self._readiness_failed(f"{what}: cannot wait for {w.describe() if w else '?'}: {state}")
                    return
                elif p.gate.timeout_s is not None and self.now() - p.since >= p.gate.timeout_s:
                    self._readiness_failed(
                        f"{what}: still waiting for {w.describe() if w else '?'} after {p.gate.timeout_s:g} s"
                    )
                    return

    def _readiness_failed(self, why: str) -> None:
        self.failures.append(why)
        self.output.launcher("ERROR", why)
        self.shutdown("a readiness condition cannot be met")

    # ---- shutdown ----------------------------------------------------------------------------------------------

    def shutdown(
        self, reason: str, *, by_action: bool = False, due_to_sigint: bool = False, event_reason: str | None = None
    ) -> None:
        """Offer a Shutdown event to the handlers, then stop every process that was running before it.

        As Jazzy: after a `shutdown` action (or a required process's exit) processes that OnShutdown handlers
        start do start, are not signalled and are waited for; on idle, Ctrl-C or a signal they are skipped.
        """
        if self.shutting_down:
            return
        self.shutting_down = True
        self._shutdown_at = self.now()
        self.output.live(None)
        self.output.launcher("WARN" if self.failures else "INFO", f"shutting down: {reason}")
        alive = [self.states[n] for n in reversed(self.start_order) if self.states[n].alive]
        context = self.engine.context
        if not by_action:
            context.is_shutdown = True
        self.engine.emit(events.Shutdown(reason=event_reason or reason, due_to_sigint=due_to_sigint))
        self.engine.defer(lambda: self._stop_all(alive))
        self.engine.process_events()

    def _stop_all(self, alive: list[ProcessState]) -> None:
        self.engine.context.is_shutdown = True
        for _, _, timer in self._timers:
            if timer.kind not in ("stop", "timer-kept"):
                timer.cancelled = True
        for p in self.pending:
            if isinstance(p.step, StartProcess):
                self.states[p.step.spec.name].state = "not started"
        self.pending.clear()
        alive = [st for st in alive if st.alive]
        if alive:
            self.output.launcher("INFO", "sending SIGINT to " + ", ".join(st.spec.name for st in alive))
            for st in alive:
                self._stop(st, signal.SIGINT if st.child is not None else signal.SIGTERM, quiet=True)

    def _stop(self, st: ProcessState, sig: int, *, quiet: bool = False) -> None:
        """Signal the group now (SIGINT, or SIGTERM for what a finished leader left); escalate later."""
        target = st.child or st.lingering
        if target is None:
            return
        if not quiet:
            self.output.launcher("INFO", f"sending {signal.Signals(sig).name} to [{st.spec.name}]")
        self._send(target, sig)
        st.state = "stopping" if st.child else st.state
        for timer in st.stop_timers:
            timer.cancelled = True
        term, kill = st.spec.sigterm_timeout_s, st.spec.sigkill_timeout_s
        st.stop_timers = [
            self._after(
                (term if sig == signal.SIGINT else 0.0) + kill,
                lambda: self._escalate(st, signal.SIGKILL, f"{kill:g} s after SIGTERM"),
                "stop",
            )
        ]
        if sig == signal.SIGINT:
            st.stop_timers.append(
                self._after(term, lambda: self._escalate(st, signal.SIGTERM, f"{term:g} s after SIGINT"), "stop")
            )

    def _escalate(self, st: ProcessState, sig: int, why: str) -> None:
        target = st.child or st.lingering
        if target is None:
            return
        self.output.launcher("WARN", f"[{st.spec.name}] still running {why}: sending {signal.Signals(sig).name}")
        self._send(target, sig)

    def _send(self, target: Child, sig: int) -> None:
        """To the process group (diffctl), or with `--signal process` to the process alone (ros2 launch)."""
        one = getattr(self.spawner, "signal_process", None)
        if (
            self.signal_scope == "process"
            and one is not None
            and any(st.child is target for st in self.states.values())
        ):
            one(target, sig)
        else:
            self.spawner.signal_group(target, sig)

    def _kill_all(self, why: str) -> None:
        alive = [st for st in self.states.values() if st.alive]
        if not alive:
            return
        self.output.launcher("WARN", f"{why}: sending SIGKILL to " + ", ".join(st.spec.name for st in alive))
        for st in alive:
            for timer in st.stop_timers:
                timer.cancelled = True
            self.spawner.signal_group(st.child or st.lingering, signal.SIGKILL)  # type: ignore[arg-type]

    def _after_event(self) -> None:
        if self.done:
            return
        self.engine.process_events()
        self._check_gates()
        self.engine.process_events()
        if not self.shutting_down and self._idle():
            if self.pending:
                # Nothing runs and nothing is scheduled: what the gates wait for can never happen.
                p = self.pending[0]
                _, w = self._gate_state(p.gate)
                self._readiness_failed(
                    f"{p.step.label}: cannot wait for {w.describe() if w else '?'}: nothing left could bring it about"
                )
            else:
                self.natural_end = True
                self.shutdown("all processes have exited")
        kept = any(not t.cancelled and t.kind == "timer-kept" for _, _, t in self._timers)
        if (
            self.shutting_down
            and not any(st.alive for st in self.states.values())
            and not self.engine.queue
            and not kept
        ):
            self._finish()
            return
        self._update_live()

    def _idle(self) -> bool:
        if any(st.alive for st in self.states.values()) or self.engine.queue:
            return False
        if self.pending and any(w.kind in ("topic", "service") for p in self.pending for w in p.gate.waits):
            return False
        return not any(not t.cancelled and t.kind in ("timer", "timer-kept", "respawn") for _, _, t in self._timers)

    def _finish(self) -> None:
        self.done = True
        took = self.now() - (self._shutdown_at or self.now())
        if self.natural_end and self.failed_processes and not self.failures:
            self.failures.append("failed: " + ", ".join(self.failed_processes))
        if self.exit_code_mode == "ros":
            self.exit_code = 1 if self.engine.errors else 0  # ros2 launch: only an exception fails the launch
        else:
            self.exit_code = 1 if self.failures else 0
        if self.failures:
            self.output.launcher("ERROR", "launch failed: " + "; ".join(self.failures))
        else:
            self.output.launcher("INFO", f"all processes stopped ({took * 1000:.0f} ms after shutdown began)")

    # ---- live line and status ----------------------------------------------------------------------------------

    def _awaited(self) -> list[str]:
        return awaited(self)

    def _live_text(self) -> str | None:
        waiting = self._awaited()
        if not waiting:
            return None
        up = [n for n in self.start_order if self.states[n].child is not None]
        return f"up: {', '.join(up) or '-'} │ waiting: {'; '.join(waiting)}"

    def _update_live(self) -> None:
        if self.shutting_down:
            return
        text = self._live_text()
        self.output.live(text)
        if text is None and self.started_all_at is None and self.start_order:
            self.started_all_at = self.now()
            running = sum(1 for st in self.states.values() if st.starts)
            took_ms = (self.started_all_at - self._t0) * 1000
            self.output.launcher("INFO", f"all {running} processes started in {took_ms:.0f} ms")

    def rows(self) -> list[ProcessRow]:
        return process_rows(self)

    def show_status(self) -> None:
        self.output.show(StatusView(self.rows()))


class _Deferred:
    """An action held back by its readiness gate: visited (with the locals it was reached with) once met."""

    def __init__(self, label: str, visit: Callable[[], None]) -> None:
        self.label = label
        self.visit = visit
