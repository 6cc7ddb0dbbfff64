"""The supervisor: runs a plan's steps, starts and watches processes, fires handlers, gates, shuts down.

It is a state machine driven from outside: `start()`, then `on_exit(pid, code)`, `on_line(name, …)`,
`on_signal(sig)` and `tick()` as things happen, until `done`. The clock and the process spawner are
injected, so unit tests run it with fakes; loop.py drives it with real processes, pipes and signals.

Shutdown (Ctrl-C, SIGTERM, SIGHUP, a required process exiting, a `shutdown` action, or nothing left to
do) sends SIGINT to every process group in reverse start order, SIGTERM after its `sigterm_timeout`,
SIGKILL after its `sigkill_timeout`, each step logged; a second Ctrl-C sends SIGKILL at once.
"""

from __future__ import annotations

import heapq
import itertools
import os
import re
import signal
import tempfile
from collections.abc import Callable
from pathlib import Path

from diffctl.errors import LaunchError
from diffctl.launch import commandline
from diffctl.launch.environment import child_env, with_tool_path
from diffctl.launch.output import Output
from diffctl.launch.plan import (
    AddHandler,
    EventInfo,
    Gate,
    Handler,
    LogMessage,
    Plan,
    ProcessSpec,
    RequestShutdown,
    SignalProcesses,
    StartProcess,
    StartTimer,
    Step,
    TargetRef,
    Wait,
    walk,
)
from diffctl.launch.process_state import (
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
from diffctl.launch.readiness import ProbePoller
from diffctl.launch.status import ProcessRow, StatusView, awaited, process_rows

STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)


class Supervisor:
    def __init__(
        self,
        plan: Plan,
        *,
        spawner: Spawner,
        output: Output,
        clock: Clock | None = None,
        log_dir: Path | None = None,
        poller: ProbePoller | None = None,
        env: dict[str, str] | None = None,
    ) -> None:
        self.plan = plan
        self.spawner = spawner
        self.output = output
        self.clock = clock or SystemClock()
        self.params_dir = (log_dir / "params") if log_dir else Path(tempfile.gettempdir()) / f"diffctl-{os.getpid()}"
        self.poller = poller
        self.base_env = with_tool_path(dict(os.environ if env is None else env))  # as default_child_env
        self.states = {name: ProcessState(spec) for name, spec in plan.processes.items()}
        self.pid_names: dict[int, str] = {}
        self.started_at: dict[int, float] = {}  # pgid → when that start of the process began
        self.handlers: list[Handler] = []
        self.fired: set[int] = set()
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
        for step in walk(plan.steps):
            for w in step.gate.waits if step.gate else ():
                if w.kind == "log" and isinstance(w.target, TargetRef) and w.target.name and w.pattern:
                    self._patterns.setdefault(w.target.name, []).append((w.pattern, re.compile(w.pattern)))

    # ---- driving -----------------------------------------------------------------------------------------------

    def now(self) -> float:
        return self.clock.monotonic()

    def start(self) -> None:
        self._t0 = self.now()
        self.run_steps(self.plan.steps)
        self._after_event()

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
        screen = st.spec.output in ("screen", "both") or stream == "stderr"
        self.output.process_line(name, stream, text, screen=screen)
        if self._io_handlers:
            pid = st.child.pid if st.child else None
            self._fire("io", name, None, EventInfo(name, pid, text=text, stream=stream))
            self._after_event()
        for pattern, compiled in self._patterns.get(name, ()):
            if pattern not in st.seen_patterns and compiled.search(text):
                st.seen_patterns.add(pattern)
                self._after_event()

    def on_signal(self, sig: int) -> None:
        if sig == signal.SIGUSR1:
            self.show_status()
        elif sig in STOP_SIGNALS:
            name = signal.Signals(sig).name
            if not self.shutting_down:
                self.shutdown("ctrl-c (SIGINT)" if sig == signal.SIGINT else f"{name} received")
            else:
                self._kill_all(f"{name} again")
            self._after_event()

    def tick(self) -> None:
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

    def run_steps(self, steps: tuple[Step, ...]) -> None:
        # As in ros2 launch, where events are handled after the actions that caused them: a handler written
        # after the process it watches still sees that process start.
        steps = tuple(sorted(steps, key=lambda s: not (isinstance(s, AddHandler) and s.gate is None)))
        for step in steps:
            if step.gate is not None and self._gate_state(step.gate)[0] is not True:
                self.pending.append(Pending(step, step.gate, self.now()))
                for w in step.gate.waits:
                    if w.kind in ("topic", "service") and self.poller is not None:
                        self.poller.want(w.kind, str(w.target))
                if isinstance(step, StartProcess):
                    self.states[step.spec.name].state = "waiting"
                continue
            self._execute(step)

    def _execute(self, step: Step) -> None:
        if isinstance(step, LogMessage):
            self.output.launcher("INFO", step.message)
        elif self.shutting_down:
            return  # nothing new starts once shutdown has begun
        elif isinstance(step, StartProcess):
            self._start(step.spec)
        elif isinstance(step, StartTimer):
            steps = step.steps
            self._after(step.period_s, lambda: self.run_steps(steps), "timer")
        elif isinstance(step, RequestShutdown):
            self.shutdown(step.reason)
        elif isinstance(step, AddHandler):
            self.handlers.append(step.handler)
        elif isinstance(step, SignalProcesses):
            self._signal_processes(step)

    def _signal_processes(self, step: SignalProcesses) -> None:
        for ref in step.targets:
            st = self.states.get(ref.name or "")
            if st is None or not st.alive:
                self.output.launcher("WARN", f"cannot signal [{ref}]: it is not running")
            elif step.signal is None:
                self._stop(st, signal.SIGINT)
            else:
                self.output.launcher("INFO", f"sending {signal.Signals(step.signal).name} to [{st.spec.name}]")
                self.spawner.signal_group(st.child or st.lingering, step.signal)  # type: ignore[arg-type]

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
        st = self.states[spec.name]
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
        self._fire("start", spec.name, None, EventInfo(spec.name, child.pid))

    def _process_exited(self, st: ProcessState, code: int, pid: int | None, ran: str) -> None:
        name = st.spec.name
        where = f"pid {pid}{ran}" if pid else "never started"
        if self.shutting_down:
            st.state = "stopped"
            self.output.launcher("INFO", f"[{name}] stopped ({describe_exit(code)}, {where})")
            if st.lingering is not None:
                # The leader went on SIGINT, the rest stayed: a non-interactive shell's background job ignores
                # SIGINT, so waiting out sigterm_timeout for it would only delay the inevitable.
                self.output.launcher("INFO", f"[{name}] left processes in its group; sending them SIGTERM")
                self._stop(st, signal.SIGTERM, quiet=True)
            return
        if code == 0:
            st.state = "exited"
            self.output.launcher("INFO", f"[{name}] finished cleanly ({where})")
        else:
            st.state = "failed"
            last = f": {st.tail[-1]}" if st.tail else ""
            self.output.launcher("ERROR", f"[{name}] {died(code)} ({where}){last}")
        self._fire("exit", name, code, EventInfo(name, pid, exit_code=code))
        if self.shutting_down:
            return
        if st.spec.required:
            why = f"required process {name!r} {'finished' if code == 0 else died(code)}"
            if code != 0:
                self.failures.append(why + (f" (last output: {st.tail[-1]!r})" if st.tail else ""))
            self.shutdown(why)
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
        elif code != 0:
            self.failed_processes.append(f"{name} ({describe_exit(code)})")
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
        return any(h.event == "io" for h in self.handlers)

    def _fire(self, event: str, name: str, code: int | None, info: EventInfo | None = None) -> None:
        for handler in list(self.handlers):
            if handler.event != event or not handler.matches(name, code):
                continue
            if event == "io" and info is not None and info.stream not in handler.streams:
                continue
            self.fired.add(id(handler))
            if handler.once:
                self.handlers.remove(handler)
            self.run_steps(handler.steps)
            if handler.callback is not None:
                self._call(handler, info or EventInfo(name, exit_code=code))

    def _call(self, handler: Handler, info: EventInfo) -> None:
        """A launch file's callable handler: what it returns is resolved now and run."""
        try:
            steps = handler.callback(info)  # type: ignore[misc]
        except LaunchError as e:
            self.failures.append(f"event handler {handler.describe_callback or ''} failed: {e}")
            self.output.launcher("ERROR", str(e))
            self.shutdown("an event handler failed")
            return
        for step in walk(steps):
            if isinstance(step, StartProcess) and step.spec.name not in self.states:
                self.states[step.spec.name] = ProcessState(step.spec)
                self.plan.processes[step.spec.name] = step.spec
        self.run_steps(steps)

    # ---- readiness ---------------------------------------------------------------------------------------------

    def _wait_state(self, w: Wait) -> bool | str:
        """True when met, False while it may still be met, or the reason it never will be."""
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
                what = p.step.spec.name if isinstance(p.step, StartProcess) else type(p.step).__name__
                if state is True:
                    self.pending.remove(p)
                    self._execute(p.step)
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

    def shutdown(self, reason: str) -> None:
        if self.shutting_down:
            return
        self.shutting_down = True  # from here on only log actions run, nothing new starts
        self._shutdown_at = self.now()
        self.output.live(None)
        self.output.launcher("WARN" if self.failures else "INFO", f"shutting down: {reason}")
        self._fire("shutdown", "", None, EventInfo("", text=reason))
        for _, _, timer in self._timers:
            timer.cancelled = True
        for p in self.pending:
            if isinstance(p.step, StartProcess):
                self.states[p.step.spec.name].state = "not started"
        self.pending.clear()
        alive = [self.states[n] for n in reversed(self.start_order) if self.states[n].alive]
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
        self.spawner.signal_group(target, sig)
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
        self._check_gates()
        if not self.shutting_down and self._idle():
            self.natural_end = True
            self.shutdown("all processes have exited")
        if self.shutting_down and not any(st.alive for st in self.states.values()):
            self._finish()
            return
        self._update_live()

    def _idle(self) -> bool:
        if any(st.alive for st in self.states.values()) or self.pending:
            return False
        return not any(not t.cancelled and t.kind in ("timer", "respawn") for _, _, t in self._timers)

    def _finish(self) -> None:
        self.done = True
        took = self.now() - (self._shutdown_at or self.now())
        if self.natural_end and self.failed_processes and not self.failures:
            self.failures.append("failed: " + ", ".join(self.failed_processes))
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
