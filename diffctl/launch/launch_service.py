"""`LaunchService`: runs launch descriptions on an asyncio loop until they are done or shut down."""

from __future__ import annotations

import asyncio
import collections.abc
import contextlib
import logging
import signal
import threading
import traceback
from collections.abc import Callable, Coroutine, Iterable
from typing import TYPE_CHECKING, Any

from . import logging as launch_logging
from ._private.loop import get_loop
from .event_handlers.on_include_launch_description import OnIncludeLaunchDescription
from .event_handlers.on_shutdown import OnShutdown
from .events.include_launch_description import IncludeLaunchDescription
from .events.shutdown import Shutdown
from .launch_context import LaunchContext
from .launch_description_entity import LaunchDescriptionEntity
from .utilities.class_tools_impl import is_a_subclass
from .utilities.signal_management import AsyncSafeSignalManager
from .utilities.visit_all_entities_and_collect_futures_impl import visit_all_entities_and_collect_futures

if TYPE_CHECKING:
    from .event import Event
    from .launch_description import LaunchDescription

_SIGINT_TEXT = 'user interrupted with ctrl-c (SIGINT)'


def _python_level_no_op(signum: int, frame: Any) -> None:
    """Installed while a run lasts: a signal needs a Python handler to reach the wakeup fd, which acts."""


@contextlib.contextmanager
def _python_handlers(signums: Iterable[int]):
    before = {signum: signal.signal(signum, _python_level_no_op) for signum in signums}
    try:
        yield
    finally:
        for signum, handler in before.items():
            # None: a handler set outside Python, which cannot be put back; the default instead
            signal.signal(signum, signal.SIG_DFL if handler is None else handler)


class _Failure:
    """The return code of a run: 0 until something fails."""

    code = 0


class LaunchService:
    """Visits the launch descriptions it is given, handles events, and shuts down.

    `run()` (or `await run_async()`) lasts until the launch is idle — no event queued, no entity with work
    in flight — or shut down, and returns 0, or 1 when an exception escaped an entity, a handler or a task
    (or the run was canceled). While it runs, a first SIGINT shuts the launch down (a second is ignored),
    SIGTERM and SIGQUIT cancel the run.

    `noninteractive`: there is no terminal, so on shutdown launch sends processes their SIGINT itself.
    `spawner` (diffctl's): what starts processes (see `diffctl.supervision`); by default a `PosixSpawner`,
    one process group per process. With a terminal, a SIGINT to launch is passed on to those groups as
    the terminal would have passed it to its foreground group; groups alive at the end are terminated.

    diffctl's policies, for whoever runs a launch (ROS's behaviour when not given):
    `output_default`: the `output` of processes that give none ('log' in ROS; 'screen' shows their stdout).
    `process_label(action, name)`: a process's final name from its name (the `name` given, else the
    executable's), instead of ROS's `name-N` with N from one counter.
    `shutdown_on_sigterm`: SIGTERM shuts the launch down in order, as a first SIGINT does (the processes get
    their SIGINT from launch, then the escalation), instead of canceling the run.
    """

    def __init__(
        self,
        *,
        argv: Iterable[str] | None = None,
        noninteractive: bool = False,
        debug: bool = False,
        spawner: Any | None = None,
        output_default: str | None = None,
        process_label: Callable[[Any, str], str] | None = None,
        shutdown_on_sigterm: bool = False,
    ) -> None:
        launch_logging.launch_config.level = logging.DEBUG if debug else logging.INFO
        self._debug = debug
        self._log = launch_logging.get_logger('launch')
        self._context = LaunchContext(argv=[] if argv is None else argv, noninteractive=noninteractive)
        if spawner is None:
            from diffctl.supervision import PosixSpawner

            spawner = PosixSpawner(logger=launch_logging.get_logger('launch.supervision'))
        self._context._spawner = spawner
        if output_default is not None:
            self._context._output_default = output_default
        self._context._process_label = process_label
        self._sigterm_shuts_down = shutdown_on_sigterm
        self._context.register_event_handler(OnIncludeLaunchDescription())
        self._context.register_event_handler(OnShutdown(on_shutdown=self._on_shutdown_event))
        self._in_flight: list[asyncio.Future] = []  # futures of visited entities whose work goes on
        # the loop of the current run, read by other threads (emit_event, shutdown): under the lock
        self._lock = threading.RLock()
        self._loop: asyncio.AbstractEventLoop | None = None
        self._task: asyncio.Task | None = None
        self._ending = False

    @property
    def context(self) -> LaunchContext:
        return self._context

    @property
    def event_loop(self) -> asyncio.AbstractEventLoop | None:
        """The loop of the current run; None between runs."""
        return self._loop

    @property
    def task(self) -> asyncio.Task | None:
        """The task of the current (or last) run."""
        return self._task

    @property
    def spawner(self) -> Any:
        """What starts this launch's processes."""
        return self._context._spawner

    # ---- from any thread -------------------------------------------------------------------------------------

    def emit_event(self, event: Event) -> None:
        """Queue `event`, from any thread; before a run it waits in the queue for it."""
        with self._lock:
            loop = self._loop
            if loop is None:
                self._context.emit_event_sync(event)
                return
            delivery = asyncio.run_coroutine_threadsafe(self._context.emit_event(event), loop)
        delivery.result()

    def include_launch_description(self, launch_description: LaunchDescription) -> None:
        """Have `launch_description` visited by the run (thread-safe)."""
        self.emit_event(IncludeLaunchDescription(launch_description))

    def shutdown(self, force_sync: bool = False) -> Coroutine | None:
        """End the current run (nothing happens between runs); thread-safe.

        On the run's loop, or while a caller drives that loop itself, it returns a coroutine to await.
        """
        with self._lock:
            if self._loop is None:
                return None
            return self._shutdown(reason='LaunchService.shutdown() called', due_to_sigint=False, force_sync=force_sync)

    # ---- a run -------------------------------------------------------------------------------------------------

    def run(self, *, shutdown_when_idle: bool = True) -> int:
        """Run on this thread's loop until done (see `run_async`); a KeyboardInterrupt does not stop it."""
        loop = get_loop()
        running = loop.create_task(self.run_async(shutdown_when_idle=shutdown_when_idle))
        while True:
            try:
                return loop.run_until_complete(running)
            except KeyboardInterrupt:
                continue
            except BaseException:
                self._abandon(loop, running)
                raise

    def _abandon(self, loop: asyncio.AbstractEventLoop, running: asyncio.Task) -> None:
        """Something broke out of the loop (SystemExit from a handler, a test's timeout): end the run now.

        No process may outlive it; and left pending on this thread's loop, the run would wake up inside the
        next service's run on it (aborting that one, or undoing its signal handling).
        """
        kill_all = getattr(self.spawner, 'kill_all', None)
        if kill_all is not None:
            kill_all()
        running.cancel()
        with contextlib.suppress(BaseException):
            loop.run_until_complete(running)

    async def run_async(self, *, shutdown_when_idle: bool = True) -> int:
        """Run on the running loop until idle (with `shutdown_when_idle`) or shut down; 0, or 1 on errors.

        Only on the main thread, and one run at a time.
        """
        if threading.current_thread() is not threading.main_thread():
            raise RuntimeError('LaunchService can only be run in the main thread.')
        outcome = _Failure()
        with self._attached() as loop:
            launch_logging.log_launch_config(logger=self._log)

            def on_loop_error(loop: asyncio.AbstractEventLoop, details: dict) -> None:
                outcome.code = 1
                loop.default_exception_handler(details)

            previous = loop.get_exception_handler()
            loop.set_exception_handler(on_loop_error)
            try:
                await self._drive(loop, shutdown_when_idle, outcome)
            finally:
                loop.set_exception_handler(previous)
                await self._stop_processes()
        return outcome.code

    @contextlib.contextmanager
    def _attached(self):
        """This run owns the loop: the context runs on it, and SIGINT, SIGTERM and SIGQUIT are ours."""
        try:
            with self._lock:
                if self._loop is not None:
                    raise RuntimeError('LaunchService cannot be run multiple times concurrently.')
                loop = get_loop()
                if self._debug:
                    loop.set_debug(True)
                self._context._running_on(loop)
                self._fresh_queue()
                self._loop = loop
            self._task = asyncio.current_task(loop)
            with self._signals(loop, self._task):
                yield loop
        finally:
            with self._lock:
                self._context._running_on(None)
                self._loop = None
                self._ending = False

    def _fresh_queue(self) -> None:
        """A queue for this run's loop (a queue serves one loop), holding what was queued before it."""
        earlier = self._context._queue
        self._context._queue = asyncio.Queue()
        while not earlier.empty():
            self._context._queue.put_nowait(earlier.get_nowait())

    @contextlib.contextmanager
    def _signals(self, loop: asyncio.AbstractEventLoop, task: asyncio.Task | None):
        heard_sigint = False

        def on_sigint(signum: int) -> None:
            nonlocal heard_sigint
            if heard_sigint:
                self._log.warning(f'{_SIGINT_TEXT} again, ignoring...')
                return
            heard_sigint = True
            self._log.warning(_SIGINT_TEXT)
            if not self._context.noninteractive:
                # each child leads a process group of its own: give them what a terminal gives its group
                self.spawner.signal_all(signal.SIGINT)
            self._shutdown(reason='ctrl-c (SIGINT)', due_to_sigint=True, force_sync=True)

        def on_termination(signum: int) -> None:
            self._log.error(f'user interrupted with ctrl-\\ ({signal.Signals(signum).name}), terminating...')
            if task is not None:
                loop.call_soon(task.cancel)

        heard_sigterm = False

        def on_sigterm(signum: int) -> None:
            nonlocal heard_sigterm
            if not self._sigterm_shuts_down:
                on_termination(signum)
            elif heard_sigterm:
                self._log.warning('terminated (SIGTERM) again, ignoring...')
            else:
                heard_sigterm = True
                self._log.warning('terminated (SIGTERM): shutting down')
                self._shutdown(reason='SIGTERM', due_to_sigint=False, force_sync=True)

        handled = (signal.SIGINT, signal.SIGTERM, signal.SIGQUIT)
        with AsyncSafeSignalManager(loop) as manager:
            manager.handle(signal.SIGINT, on_sigint)
            manager.handle(signal.SIGTERM, on_sigterm)
            manager.handle(signal.SIGQUIT, on_termination)
            with _python_handlers(handled):
                yield

    async def _drive(self, loop: asyncio.AbstractEventLoop, shutdown_when_idle: bool, outcome: _Failure) -> None:
        """Handle events and watch entities' futures until the run may end."""
        consumer: asyncio.Task | None = None
        try:
            while True:
                try:
                    idle = self._is_idle()
                    if idle and self._ending:
                        return
                    if idle and shutdown_when_idle:
                        await self._shutdown_now(reason='idle')
                        continue
                    if consumer is None or consumer.done():
                        consumer = loop.create_task(self._next_event())
                    watched: list[asyncio.Future] = [consumer]
                    if self._context._queue.empty():
                        watched += self._in_flight + self._context._awaited
                    finished, _ = await asyncio.wait(watched, return_when=asyncio.FIRST_COMPLETED)
                    self._raise_failure(finished)
                except KeyboardInterrupt:
                    continue
                except asyncio.CancelledError:
                    self._log.error('run task was canceled')
                    outcome.code = 1
                    return
                except Exception as problem:
                    # the launch ends, but in order: its entities shut down as for any shutdown
                    await self._shutdown_now(reason=self._report(problem))
                    outcome.code = 1
        finally:
            if consumer is not None and not consumer.done():
                consumer.cancel()

    def _is_idle(self) -> bool:
        """No event queued and no entity with work in flight (launch_pytest's examples ask it too)."""
        self._in_flight = [future for future in self._in_flight if not future.done()]
        context = self._context
        context._awaited = [future for future in context._awaited if not future.done()]
        return not self._in_flight and not context._awaited and context._queue.empty()

    def _raise_failure(self, finished: set[asyncio.Future]) -> None:
        """Raise the exception of one finished future; those of others are logged."""
        failures = [done.exception() for done in finished if not done.cancelled() and done.exception()]
        if not failures:
            return
        self._log.debug('An exception was raised in an async action/event')
        for extra in failures[1:]:
            self._log.error(extra)
        raise failures[0]

    def _report(self, problem: Exception) -> str:
        """Log an error that ends the launch, in one line naming where in the user's files it arose."""
        from ._private.locate import user_location

        text = str(problem)
        where = user_location(problem)
        if where and where not in text:
            text = f'{where}: {text}'
        line = f'Caught exception in launch (see debug for traceback): {text}'
        self._log.debug(''.join(traceback.format_exception(problem)))
        self._log.error(line)
        return line

    async def _stop_processes(self) -> None:
        stop = getattr(self.spawner, 'shutdown', None)
        if stop is not None:
            with contextlib.suppress(asyncio.CancelledError):
                await asyncio.shield(stop())

    # ---- events ------------------------------------------------------------------------------------------------

    async def _next_event(self) -> None:
        queue = self._context._queue
        event = await queue.get()
        # The events queued when this turn of the loop began are handled in it, in order; those their handlers
        # queue wait for a turn, so that what these started runs first. A turn per event (with the driver's wait
        # around each) made stopping 50 processes, a SignalProcess each, cost twice the launcher's CPU.
        waiting = queue.qsize()
        try:
            await self._dispatch(event)
            for _ in range(waiting):
                await self._dispatch(queue.get_nowait())
        except SystemExit as leaving:
            # out of the loop, it would leave this run half done on a loop others go on using: the launch
            # fails and shuts down instead, as for any exception
            raise RuntimeError(f'SystemExit({leaving.code!r}) raised while launching') from leaving

    async def _dispatch(self, event: Event) -> None:
        """Offer `event` to every handler registered now, newest first; visit what each gives."""
        context = self._context
        debug = self._log.isEnabledFor(logging.DEBUG)
        if debug:
            self._log.debug(f"processing event: '{event}'")
        for handler in context._handlers_for(event):
            if not handler.matches(event):
                continue
            if debug:
                self._log.debug(f"processing event: '{event}' ✓ '{handler}'")
            context._save('locals')
            try:
                given = handler.handle(event, context)
                many = given if isinstance(given, collections.abc.Iterable) else [given]
                for entity in many:
                    if entity is not None:
                        self._visit(entity)
            finally:
                context._restore('locals')

    def _visit(self, entity: Any) -> None:
        if not is_a_subclass(entity, LaunchDescriptionEntity):
            raise RuntimeError(f"expected a LaunchDescriptionEntity from event_handler, got '{entity}'")
        for _, future in visit_all_entities_and_collect_futures(entity, self._context):
            self._in_flight.append(future)

    # ---- shutting down -----------------------------------------------------------------------------------------

    def _on_shutdown_event(self, event: Event, context: LaunchContext) -> None:
        self._ending = True
        context._mark_ending()

    async def _shutdown_now(self, *, reason: str) -> None:
        pending = self._shutdown(reason=reason, due_to_sigint=False)
        if pending is not None:
            await pending

    def _shutdown(self, *, reason: str, due_to_sigint: bool, force_sync: bool = False) -> Coroutine | None:
        """Mark the launch as ending and, the first time, emit the Shutdown event.

        Returns the coroutine queueing it when the caller is on the run's loop (or drives it): await it.
        """
        queued = None
        if not self._ending:
            event = Shutdown(reason=reason, due_to_sigint=due_to_sigint)
            try:
                here = asyncio.get_running_loop()
            except RuntimeError:
                here = None
            loop = self._loop
            if force_sync:
                self._context.emit_event_sync(event)
            elif loop is not None and (here is loop or not loop.is_running()):
                # on the loop, or its run is paused while the caller drives the loop (run_until_complete,
                # as ros2/launch's own tests do): waiting for it from here would never end
                queued = self._context.emit_event(event)
            else:
                self.emit_event(event)
        self._ending = True
        self._context._mark_ending()
        return queued
