"""`LaunchService`: runs launch descriptions on an asyncio loop until they are done or shut down."""

from __future__ import annotations

import asyncio
import collections.abc
import contextlib
import logging
import signal
import threading
import traceback
from collections.abc import Coroutine, Iterable
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
    from .some_entities_type import SomeEntitiesType

_HANDLED_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGQUIT)


def _ignore(signum: int, frame: Any) -> None:
    """The Python-level handler while launch runs: the wakeup fd does the work (see run_async)."""


class LaunchService:
    """Visits the entities of the launch descriptions it is given, handles events, and shuts down.

    `run()` (or `await run_async()`) runs until idle — no event queued, no entity with work in flight — or
    until a shutdown; it returns 0, or 1 when an exception escaped an entity or the run was canceled.
    While it runs, SIGINT starts a shutdown (a second one is ignored) and SIGTERM / SIGQUIT cancel the run.

    `noninteractive`: there is no terminal, so processes get their SIGINT from launch on shutdown.
    `spawner` (diffctl): what starts processes (`diffctl.supervision`); by default a `PosixSpawner`, which
    runs each process in its own process group. With a terminal, a SIGINT reaching launch is passed on to
    those groups, as the terminal would have done for processes in its foreground group; when the run
    ends, groups still alive are terminated.
    """

    def __init__(
        self,
        *,
        argv: Iterable[str] | None = None,
        noninteractive: bool = False,
        debug: bool = False,
        spawner: Any | None = None,
    ) -> None:
        launch_logging.launch_config.level = logging.DEBUG if debug else logging.INFO
        self.__debug = debug
        self.__argv = argv if argv is not None else []
        self.__logger = launch_logging.get_logger('launch')

        self.__context = LaunchContext(argv=self.__argv, noninteractive=noninteractive)
        if spawner is None:
            from diffctl.supervision import PosixSpawner

            spawner = PosixSpawner(logger=launch_logging.get_logger('launch.supervision'))
        self.__context._spawner = spawner
        self.__context.register_event_handler(OnIncludeLaunchDescription())
        self.__context.register_event_handler(OnShutdown(on_shutdown=self.__on_shutdown))

        self._entity_future_pairs: list[tuple[LaunchDescriptionEntity, asyncio.Future]] = []
        # guards __loop_from_run_thread, read from other threads by emit_event() and shutdown()
        self.__loop_from_run_thread_lock = threading.RLock()
        self.__loop_from_run_thread: asyncio.AbstractEventLoop | None = None
        self.__this_task: asyncio.Task | None = None
        self.__shutting_down = False

    @property
    def spawner(self) -> Any:
        """What starts this launch's processes."""
        return self.__context._spawner

    # ---- events from anywhere ------------------------------------------------------------------------------

    def emit_event(self, event: Event) -> None:
        """Queue an event, from any thread; before the service runs it waits in the queue."""
        future = None
        with self.__loop_from_run_thread_lock:
            if self.__loop_from_run_thread is not None:
                future = asyncio.run_coroutine_threadsafe(
                    self.__context.emit_event(event), self.__loop_from_run_thread)
            else:
                self.__context.emit_event_sync(event)
        if future is not None:
            future.result()

    def include_launch_description(self, launch_description: LaunchDescription) -> None:
        """Have the service visit `launch_description` (thread-safe)."""
        self.emit_event(IncludeLaunchDescription(launch_description))

    # ---- idleness ------------------------------------------------------------------------------------------

    def _prune_and_count_entity_future_pairs(self) -> int:
        self._entity_future_pairs = [pair for pair in self._entity_future_pairs if not pair[1].done()]
        return len(self._entity_future_pairs)

    def _prune_and_count_context_completion_futures(self) -> int:
        context = self.__context
        context._completion_futures = [f for f in context._completion_futures if not f.done()]
        return len(context._completion_futures)

    def _is_idle(self) -> bool:
        pending = self._prune_and_count_entity_future_pairs() + self._prune_and_count_context_completion_futures()
        return pending == 0 and self.__context._event_queue.empty()

    # ---- the loop ------------------------------------------------------------------------------------------

    @contextlib.contextmanager
    def _prepare_run_loop(self):
        """Bind the context to this thread's loop and take over SIGINT, SIGTERM and SIGQUIT while running."""
        try:
            with self.__loop_from_run_thread_lock:
                if self.__loop_from_run_thread is not None:
                    raise RuntimeError('LaunchService cannot be run multiple times concurrently.')
                loop = get_loop()
                if self.__debug:
                    loop.set_debug(True)
                self.__context._set_asyncio_loop(loop)
                # a fresh queue for this loop, with what was queued before the run
                queue: asyncio.Queue = asyncio.Queue()
                old = self.__context._event_queue
                while not old.empty():
                    queue.put_nowait(old.get_nowait())
                self.__context._event_queue = queue
                self.__loop_from_run_thread = loop
            task = asyncio.current_task(loop)
            self.__this_task = task
            with self.__signals(loop, task):
                yield loop, task
        finally:
            with self.__loop_from_run_thread_lock:
                self.__context._set_asyncio_loop(None)
                self.__loop_from_run_thread = None
                self.__shutting_down = False

    @contextlib.contextmanager
    def __signals(self, loop: asyncio.AbstractEventLoop, task: asyncio.Task | None):
        sigint_seen = False

        def on_sigint(signum: int) -> None:
            nonlocal sigint_seen
            message = 'user interrupted with ctrl-c (SIGINT)'
            if sigint_seen:
                self.__logger.warning(f'{message} again, ignoring...')
                return
            sigint_seen = True
            self.__logger.warning(message)
            if not self.__context.noninteractive:
                # the children run in process groups of their own: pass on what a terminal sends its group
                self.spawner.signal_all(signal.SIGINT)
            self._shutdown(reason='ctrl-c (SIGINT)', due_to_sigint=True, force_sync=True)

        def on_terminate(signum: int) -> None:
            name = signal.Signals(signum).name
            self.__logger.error(f'user interrupted with ctrl-\\ ({name}), terminating...')
            if task is not None:
                loop.call_soon(task.cancel)

        previous = {}
        with AsyncSafeSignalManager(loop) as manager:
            manager.handle(signal.SIGINT, on_sigint)
            manager.handle(signal.SIGTERM, on_terminate)
            manager.handle(signal.SIGQUIT, on_terminate)
            try:
                for signum in _HANDLED_SIGNALS:
                    previous[signum] = signal.signal(signum, _ignore)
                yield
            finally:
                for signum, handler in previous.items():
                    # None: a handler installed outside Python, which cannot be put back; the default then
                    signal.signal(signum, signal.SIG_DFL if handler is None else handler)

    async def _process_one_event(self) -> None:
        event = await self.__context._event_queue.get()
        try:
            await self.__process_event(event)
        except SystemExit as exc:
            # out of the loop, it would leave this run half done on a loop others go on using: the launch
            # fails and shuts down instead, as for any exception
            raise RuntimeError(f'SystemExit({exc.code!r}) raised while launching') from exc

    async def __process_event(self, event: Event) -> None:
        context = self.__context
        self.__logger.debug(f"processing event: '{event}'")
        for handler in tuple(context._event_handlers):
            if not handler.matches(event):
                continue
            self.__logger.debug(f"processing event: '{event}' ✓ '{handler}'")
            context._push_locals()
            try:
                entities = handler.handle(event, context)
                if not isinstance(entities, collections.abc.Iterable):
                    entities = (entities,)
                for entity in [e for e in entities if e is not None]:
                    if not is_a_subclass(entity, LaunchDescriptionEntity):
                        raise RuntimeError(
                            f"expected a LaunchDescriptionEntity from event_handler, got '{entity}'")
                    self._entity_future_pairs.extend(visit_all_entities_and_collect_futures(entity, context))
            finally:
                context._pop_locals()

    async def run_async(self, *, shutdown_when_idle: bool = True) -> int:
        """Run on the current loop until idle (with `shutdown_when_idle`) or shut down; 0 or 1 (errors).

        Only from the main thread, never twice at once.
        """
        if threading.current_thread() is not threading.main_thread():
            raise RuntimeError('LaunchService can only be run in the main thread.')
        return_code = 0
        with self._prepare_run_loop() as (loop, _task):
            launch_logging.log_launch_config(logger=self.__logger)

            def on_exception(loop: asyncio.AbstractEventLoop, context: dict) -> None:
                nonlocal return_code
                return_code = 1
                loop.default_exception_handler(context)

            previous_handler = loop.get_exception_handler()
            loop.set_exception_handler(on_exception)
            event_task: asyncio.Task | None = None
            try:
                while True:
                    try:
                        idle = self._is_idle()
                        if not self.__shutting_down and shutdown_when_idle and idle:
                            pending = self._shutdown(reason='idle', due_to_sigint=False)
                            if pending is not None:
                                await pending
                            continue
                        if self.__shutting_down and idle:
                            break
                        waiting: list = []
                        if self.__context._event_queue.empty():
                            waiting = [pair[1] for pair in self._entity_future_pairs]
                            waiting.extend(self.__context._completion_futures)
                        if event_task is None or event_task.done():
                            event_task = loop.create_task(self._process_one_event())
                        waiting.append(event_task)
                        done, _ = await asyncio.wait(waiting, return_when=asyncio.FIRST_COMPLETED)
                        first = None
                        for finished in done:
                            if finished.cancelled():
                                continue
                            exc = finished.exception()
                            if exc is None:
                                continue
                            if first is None:
                                self.__logger.debug('An exception was raised in an async action/event')
                                first = exc
                            else:
                                self.__logger.error(exc)
                        if first is not None:
                            raise first
                    except KeyboardInterrupt:
                        continue
                    except asyncio.CancelledError:
                        self.__logger.error('run task was canceled')
                        return_code = 1
                        break
                    except Exception as exc:
                        message = self.__report(exc)
                        pending = self._shutdown(reason=message, due_to_sigint=False)
                        if pending is not None:
                            await pending
                        return_code = 1
                        continue  # let the entities shut down properly
            finally:
                if event_task is not None and not event_task.done():
                    event_task.cancel()
                loop.set_exception_handler(previous_handler)
                await self.__end_processes()
        return return_code

    def __report(self, exc: Exception) -> str:
        from ._private.locate import user_location

        where = user_location(exc)
        text = str(exc)
        if where and where not in text:
            text = f'{where}: {text}'
        message = f'Caught exception in launch (see debug for traceback): {text}'
        self.__logger.debug(''.join(traceback.format_exception(exc)))
        self.__logger.error(message)
        return message

    async def __end_processes(self) -> None:
        shutdown = getattr(self.spawner, 'shutdown', None)
        if shutdown is None:
            return
        try:
            await asyncio.shield(shutdown())
        except asyncio.CancelledError:
            pass

    def run(self, *, shutdown_when_idle: bool = True) -> int:
        """Run the service on this thread's loop until done (see `run_async`); KeyboardInterrupt is ignored."""
        loop = get_loop()
        run_task = loop.create_task(self.run_async(shutdown_when_idle=shutdown_when_idle))
        while True:
            try:
                return loop.run_until_complete(run_task)
            except KeyboardInterrupt:
                continue
            except BaseException:
                # something aborted the loop (SystemExit from a handler, a test's timeout): the run cannot go
                # on, and no process may outlive it
                kill_all = getattr(self.spawner, 'kill_all', None)
                if kill_all is not None:
                    kill_all()
                # the loop is this thread's for the next service too: left pending, this run would wake up in
                # that one's run_until_complete (and abort it, or undo its signal handling); ended here, its
                # cleanup runs now
                run_task.cancel()
                try:
                    loop.run_until_complete(run_task)
                except BaseException:
                    pass
                raise

    # ---- shutdown ------------------------------------------------------------------------------------------

    def __on_shutdown(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        self.__shutting_down = True
        self.__context._set_is_shutdown(True)
        return None

    def _shutdown(self, *, reason: str, due_to_sigint: bool, force_sync: bool = False) -> Coroutine | None:
        result = None
        if not self.__shutting_down:
            event = Shutdown(reason=reason, due_to_sigint=due_to_sigint)
            try:
                current = asyncio.get_running_loop()
            except RuntimeError:
                current = None
            loop = self.__loop_from_run_thread
            if force_sync:
                self.__context.emit_event_sync(event)
            elif current is not None and current is loop:
                result = self.__context.emit_event(event)
            elif loop is not None and not loop.is_running():
                # its run_async is paused (a caller drives the loop with run_until_complete, as ros2/launch's
                # own tests do): waiting for it here would never end; the caller schedules the coroutine
                result = self.__context.emit_event(event)
            else:
                self.emit_event(event)
        self.__shutting_down = True
        self.__context._set_is_shutdown(True)
        return result

    def shutdown(self, force_sync: bool = False) -> Coroutine | None:
        """Shut the running service down (nothing when it does not run); thread-safe.

        Called on the service's loop it returns a coroutine to await.
        """
        with self.__loop_from_run_thread_lock:
            if self.__loop_from_run_thread is not None:
                return self._shutdown(
                    reason='LaunchService.shutdown() called', due_to_sigint=False, force_sync=force_sync)
        return None

    @property
    def context(self) -> LaunchContext:
        return self.__context

    @property
    def event_loop(self) -> asyncio.AbstractEventLoop | None:
        """The loop the service runs on, None when it does not run."""
        return self.__loop_from_run_thread

    @property
    def task(self) -> asyncio.Task | None:
        """The task running the service."""
        return self.__this_task
