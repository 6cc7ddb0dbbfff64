"""One launch running on a thread of its own: the LaunchService that launch tests talk to.

The engine's event loop (diffctl/launch_legacy/loop.py) is built for the main thread of `diffctl launch`: it takes
signals through a wake-up pipe. A launch test runs its test methods while the launch runs, so here the loop
runs on a thread of its own: child exits come through pidfds (no SIGCHLD needed), and everything the test
thread asks of the launch (shut down, include a description, emit an event) is queued and done on the launch
thread between two steps of the loop, never in the middle of one.

diffctl's components are forked from a fork server (as `diffctl launch` does) only when asked (`use_fork_server`):
measured on the tutorial car's smoke test (2 cores), one test alone starts them sooner by plain exec (the
zygote's imports compete with the test's own), and tests side by side gained nothing measurable.
"""

from __future__ import annotations

import contextlib
import os
import queue
import selectors
import threading
from collections.abc import Callable
from pathlib import Path
from typing import IO, Any

from diffctl.launch_legacy.loop import EventLoop
from diffctl.launch_legacy.output import Output
from diffctl.launch_legacy.plan import Plan
from diffctl.launch_legacy.supervisor import Supervisor


class _ThreadLoop(EventLoop):
    """The engine's loop without signal handling: exits are seen through pidfds, requests through a queue."""

    def __init__(self, server: Any = None) -> None:
        super().__init__(watch_stdin=False, server=server)
        self.requests: queue.SimpleQueue[Callable[[], None]] = queue.SimpleQueue()
        self._pidfds: dict[int, int] = {}

    def _add_pipes(self, name: str, pid: int, stdout: IO[bytes], stderr: IO[bytes]) -> None:
        super()._add_pipes(name, pid, stdout, stderr)
        try:
            fd = os.pidfd_open(pid)
        except (OSError, AttributeError):
            return  # the loop's short select timeout still notices the exit
        self._pidfds[pid] = fd
        self.selector.register(fd, selectors.EVENT_READ, ("pidfd", pid))

    def call(self, function: Callable[[], None]) -> None:
        self.requests.put(function)
        self.wake()

    def run(self, supervisor: Supervisor) -> int:
        self.supervisor = supervisor
        try:
            supervisor.start()
            self._drain_requests()
            self._reap(orphans=False)
            while not supervisor.done:
                deadline = supervisor.next_deadline()
                timeout = 0.2 if deadline is None else min(0.2, max(0.0, deadline - supervisor.now()))
                exited = False
                for key, _ in self.selector.select(timeout):
                    if key.data == "wake":
                        self._signals()
                    elif isinstance(key.data, tuple):
                        exited = True
                        self._close_pidfd(key.data[1])
                    else:
                        self._read(key.data)
                self._drain_requests()
                self._reap(orphans=exited)
                supervisor.tick()
            return supervisor.exit_code
        except BaseException:
            self.spawner.kill_all()
            raise
        finally:
            for pid in list(self._pidfds):
                self._close_pidfd(pid)
            self._close()

    def _close_pidfd(self, pid: int) -> None:
        fd = self._pidfds.pop(pid, None)
        if fd is not None:
            with contextlib.suppress(KeyError, ValueError, OSError):
                self.selector.unregister(fd)
            os.close(fd)

    def _drain_requests(self) -> None:
        while True:
            try:
                function = self.requests.get_nowait()
            except queue.Empty:
                return
            function()


_FORK_PRELOAD: Any = None


def use_fork_server(preload: Any) -> None:
    """Fork diffctl's components from a zygote that imports `preload` (the CLI layer's list) once per launch."""
    global _FORK_PRELOAD
    _FORK_PRELOAD = preload


def _fork_server() -> Any:
    from diffctl.launch_legacy import fork_server
    from diffctl.launch_legacy.environment import default_child_env
    from diffctl.testing.zygotes import take_inherited

    env = default_child_env(dict(os.environ))  # the test's own bus: the zygote's children get it
    if not fork_server.enabled(env):
        return None
    inherited = take_inherited(env)  # this test was forked from a preloaded interpreter (zygotes.py)
    if inherited is not None:
        return inherited
    if _FORK_PRELOAD is None:
        return None
    return fork_server.ForkServer(env, preexec=fork_server.dies_with_launcher(), preload=_FORK_PRELOAD)


class _TestSupervisor(Supervisor):
    """The supervisor of a launch under test: with `keep_alive`, no shutdown when nothing is left running."""

    keep_alive = False

    def _idle(self) -> bool:
        return False if self.keep_alive else super()._idle()


class LaunchService:
    """A launch description run on its own thread (launch.LaunchService's role for launch_testing).

    `start()` visits the description on the launch thread; `shutdown()` stops it (Shutdown event, then SIGINT
    to the processes, escalating); `wait()` joins. Thread-safe: anything may be asked from the test thread.
    """

    def __init__(
        self,
        description: Any,
        arguments: dict[str, str] | None = None,
        *,
        source: str = "<launch test>",
        log_dir: Path | None = None,
        output: Output | None = None,
        shutdown_when_idle: bool = True,
        output_default: str = "log",
    ) -> None:
        self.description = description
        self.arguments = dict(arguments or {})
        self.loop = _ThreadLoop(_fork_server())
        self.output = output or Output(log_dir=log_dir, live=False)
        plan = Plan(source, [], (), {}, description=description, launch_arguments=self.arguments)
        self.supervisor = _TestSupervisor(
            plan,
            spawner=self.loop.spawner,
            output=self.output,
            log_dir=log_dir,
            env=dict(os.environ),
            output_default=output_default,
            exit_code_mode="ros",
        )
        self.supervisor.keep_alive = not shutdown_when_idle
        if self.loop.spawner.fork_server is not None:
            try:
                # The first visit, here: a launch that starts none of diffctl's components does not keep a fork
                # server importing for nothing.
                self.supervisor.prepare()
            except BaseException:
                self.loop.spawner.close(kill_fork_server=True)
                raise
            from diffctl.launch_legacy.fork_server import is_component

            if not self.supervisor.may_start_components(is_component):
                self.loop.spawner.drop_fork_server()
        self.return_code: int | None = None
        self.error: BaseException | None = None
        self.started = threading.Event()
        self._thread = threading.Thread(target=self._run, name="launch", daemon=True)

    # ---- running -----------------------------------------------------------------------------------------------

    @property
    def context(self) -> Any:
        return self.supervisor.engine.context

    @property
    def engine(self) -> Any:
        return self.supervisor.engine

    def start(self) -> None:
        self._thread.start()

    def _run(self) -> None:
        try:
            self.return_code = self.loop.run(self.supervisor)
        except BaseException as e:  # handed to the test thread: a bad description is the test's error
            self.error = e
            self.return_code = 1
        finally:
            self.started.set()

    @property
    def running(self) -> bool:
        return self._thread.is_alive()

    def _is_idle(self) -> bool:
        """No process running and nothing pending (what launch_pytest's examples check after shutdown)."""
        return not self.running or self.supervisor._idle()

    @property
    def event_loop(self) -> Any:
        """The loop while the launch runs, None once it ended (as LaunchService.event_loop)."""
        return self.loop if self.running else None

    def wait(self, timeout: float | None = None) -> bool:
        """Wait until the launch has ended (every process reaped); False on timeout."""
        self._thread.join(timeout)
        return not self._thread.is_alive()

    def run(self) -> int:
        """Run to the end on this thread's behalf (start + wait), as LaunchService.run()."""
        self.start()
        self.wait()
        if self.error is not None:
            raise self.error
        return self.return_code or 0

    # ---- requests from other threads ---------------------------------------------------------------------------

    def call(self, function: Callable[[], None]) -> None:
        """Run `function` on the launch thread between two steps of the loop."""
        if self._thread.is_alive():
            self.loop.call(function)

    def shutdown(self, reason: str = "tests finished") -> None:
        def stop() -> None:
            self.supervisor.keep_alive = False
            self.supervisor.shutdown(reason)

        self.call(stop)

    def kill(self) -> None:
        """Stop everything now (SIGKILL to every process group): a test that ran out of time."""
        self.call(lambda: self.supervisor._kill_all("test timed out"))

    def include_launch_description(self, description: Any) -> None:
        """Visit `description` now, as an IncludeLaunchDescription event would."""
        engine = self.engine

        def include() -> None:
            engine.visit_and_flush(lambda: engine.visit(description))
            self.supervisor._after_event()

        self.call(include)

    def emit_event(self, event: Any) -> None:
        def emit() -> None:
            self.engine.emit(event)
            self.supervisor._after_event()

        self.call(emit)

    emit_event_sync = emit_event
