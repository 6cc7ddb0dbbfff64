"""rclpy.executors: Single- and MultiThreadedExecutor with rclpy's scheduling.

One wait yields, in order: tasks in progress (newest first), ready waitables, then node by node its ready
timers, subscriptions, guard conditions, clients and services — one callback per ready entity per wait, so
a busy subscription cannot starve a timer. An entity handed out is left out of the next waits until its
handler has taken its work (`_executor_event`); callback groups decide whether a handler may begin. The wait
itself is `waiting.SIGNAL`: Zenoh threads, timers' due times, guards, tasks and shutdown end it.
"""

from __future__ import annotations

import itertools
import os
import threading
import time
import warnings
import weakref
from collections.abc import Callable, Generator
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from diffctl.bus.session import before_close, exiting
from diffctl.client import waiting
from diffctl.client.context import Context, all_contexts, get_default_context
from diffctl.client.exceptions import RCLError
from diffctl.client.signals import shut_down_by_signal
from diffctl.client.task import Future, Task


class ExternalShutdownException(Exception):
    """The context was shut down (rclpy.shutdown() or a signal) while an executor was waiting."""


class ShutdownException(Exception):
    """The executor itself was shut down."""


class TimeoutException(Exception):
    """No work became ready within the timeout."""


class ConditionReachedException(Exception):
    """The wait condition became true."""


class TimeoutObject:
    """A timeout that spin_until_future_complete shortens as time passes."""

    def __init__(self, timeout: float) -> None:
        self.timeout = timeout


class _WorkTracker:
    """Callbacks running now, per thread: shutdown() waits for the others' callbacks, never for its caller's own
    (rclpy.shutdown() inside a timer callback would otherwise wait for itself forever; rclpy's returns)."""

    def __init__(self) -> None:
        self._num_work_executing = 0
        self._by_thread: dict[int, int] = {}
        self._cond = threading.Condition()

    def __enter__(self) -> None:
        me = threading.get_ident()
        with self._cond:
            self._num_work_executing += 1
            self._by_thread[me] = self._by_thread.get(me, 0) + 1

    def __exit__(self, *exc: Any) -> None:
        me = threading.get_ident()
        with self._cond:
            self._num_work_executing -= 1
            left = self._by_thread.pop(me, 1) - 1
            if left:
                self._by_thread[me] = left
            self._cond.notify_all()

    def wait(self, timeout_sec: float | None = None) -> bool:
        if timeout_sec is not None and timeout_sec < 0:
            timeout_sec = None
        me = threading.get_ident()
        with self._cond:
            return self._cond.wait_for(
                lambda: self._num_work_executing - self._by_thread.get(me, 0) == 0, timeout_sec
            )


def _timeout_s(timeout_sec: Any) -> float | None:
    t = timeout_sec.timeout if isinstance(timeout_sec, TimeoutObject) else timeout_sec
    if t is None or t < 0:
        return None
    return float(t)


_live_executors: weakref.WeakSet[Executor] = weakref.WeakSet()
EXIT_WAIT_S = 2.0  # how long the exit waits for callbacks in flight on executor threads


class _Spinners:
    """The threads inside an executor's spin_once, each with the number of its current entry: the exit waits
    until each has left the call it was in, which a thread spinning again at once (rclpy.spin's loop) does
    although it is hardly ever outside one."""

    def __init__(self) -> None:
        self._cond = threading.Condition()
        self._entries = itertools.count(1)
        self._inside: dict[int, tuple[int, int]] = {}  # thread ident → (entry number, depth)

    def __enter__(self) -> None:
        me = threading.get_ident()
        with self._cond:
            entry, depth = self._inside.get(me, (next(self._entries), 0))
            self._inside[me] = (entry, depth + 1)

    def __exit__(self, *exc: Any) -> None:
        me = threading.get_ident()
        with self._cond:
            entry, depth = self._inside.pop(me)
            if depth > 1:
                self._inside[me] = (entry, depth - 1)
            else:
                self._cond.notify_all()

    def wait_left(self, timeout_s: float) -> bool:
        """Wait until every other thread inside a spin_once now has left it."""
        me = threading.get_ident()
        with self._cond:
            now = {t: entry for t, (entry, _) in self._inside.items() if t != me}
            return self._cond.wait_for(
                lambda: all(self._inside.get(t, (0, 0))[0] != entry for t, entry in now.items()), timeout_s)


_spinners = _Spinners()


def _only_spins(thread: threading.Thread) -> bool:
    """Whether `thread` was started to spin an executor (`Thread(target=executor.spin)`, `rclpy.spin`), so it
    has nothing left to do once its spin returns. (threading keeps the target until the thread's run ends.)"""
    target = getattr(thread, "_target", None)
    if isinstance(getattr(target, "__self__", None), Executor):
        return getattr(target, "__name__", "") in ("spin", "spin_until_future_complete")
    from diffctl.client import runtime

    return target in (runtime.spin, runtime.spin_until_future_complete)


def _stop_executors() -> None:
    """At session close (exit at the latest): executors spinning in other threads stop, and the callbacks
    they are running finish, before the session goes (else they publish into a closed session, or are inside
    a Zenoh call when the interpreter finalizes).

    At exit, also when the program never called rclpy.shutdown(): once every wait has ended quietly (a stopped
    executor's), the contexts are shut down, which ends the spin loops (rclpy.spin's watches only its context;
    shut down first, a SingleThreadedExecutor's wait would raise ExternalShutdownException into the program's
    thread), and a thread that only spun (`Thread(target=executor.spin, daemon=True)`) is waited for to its end:
    nothing waits for a daemon, and finalization cuts off whatever it is still doing."""
    for ex in list(_live_executors):
        # The base class's: a MultiThreadedExecutor's pool joins without a bound, and its threads are joined
        # at exit anyway (the caller's own callback is never waited for, see _WorkTracker).
        Executor.shutdown(ex, timeout_sec=EXIT_WAIT_S)
    if not exiting():
        return
    deadline = time.monotonic() + EXIT_WAIT_S
    _spinners.wait_left(EXIT_WAIT_S)
    for ctx in all_contexts():
        ctx.try_shutdown()
    me = threading.current_thread()
    for t in threading.enumerate():
        if t is not me and t.daemon and _only_spins(t):
            t.join(max(0.0, deadline - time.monotonic()))


before_close(_stop_executors, first=True)


class Executor:
    """The base: nodes, tasks and the wait; subclasses decide which thread runs a handler."""

    _notify_on_handler = False
    # Whether this class's spin_once lets a wait's ExternalShutdownException out (rclpy's
    # MultiThreadedExecutor swallows it: its spin just ends when a signal shuts the context down)
    _raises_external_shutdown = True

    def __init__(self, *, context: Context | None = None) -> None:
        self._context = get_default_context() if context is None else context
        # rclpy's executor makes a guard condition in its context at once: before init there is no context
        # handle to enter, after shutdown rcl refuses it
        if not self._context._init_called:
            raise TypeError("'NoneType' object does not support the context manager protocol")
        if not self._context._ok:
            raise RCLError("failed to create guard_condition: the given context is not valid, either rcl_init() was "
                           "not called or rcl_shutdown() was called., at /project/src/rcl/guard_condition.c:67")
        self._nodes: set[Any] = set()
        self._nodes_lock = threading.RLock()
        self._tasks: list[tuple[Task, Any, Any]] = []
        self._tasks_lock = threading.Lock()
        self._is_shutdown = False
        self._work_tracker = _WorkTracker()
        _live_executors.add(self)
        self._shutdown_lock = threading.Lock()
        self._cb_iter: Generator[tuple[Task, Any, Any], None, None] | None = None
        self._cb_asked: Any = None
        self._context.on_shutdown(self.wake)

    @property
    def context(self) -> Context:
        return self._context

    def __enter__(self) -> Executor:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.shutdown()

    def create_task(self, callback: Callable[..., Any], *args: Any, **kwargs: Any) -> Task:
        task = Task(callback, args, kwargs, executor=self)
        with self._tasks_lock:
            self._tasks.append((task, None, None))
        waiting.notify()
        return task

    def shutdown(self, timeout_sec: float | None = None) -> bool:
        with self._shutdown_lock:
            if not self._is_shutdown:
                self._is_shutdown = True
                waiting.notify()
        if not self._work_tracker.wait(timeout_sec):
            return False
        with self._nodes_lock:
            self._nodes = set()
        self._cb_iter = None
        self._cb_asked = None
        return True

    def add_node(self, node: Any) -> bool:
        with self._nodes_lock:
            if node not in self._nodes:
                self._nodes.add(node)
                node.executor = self
                waiting.notify()
                return True
            return False

    def remove_node(self, node: Any) -> None:
        with self._nodes_lock:
            if node in self._nodes:
                self._nodes.remove(node)
                waiting.notify()

    def wake(self) -> None:
        waiting.notify()

    def get_nodes(self) -> list[Any]:
        with self._nodes_lock:
            return list(self._nodes)

    def spin(self) -> None:
        while self._context.ok() and not self._is_shutdown:
            self.spin_once()
        if self._raises_external_shutdown and shut_down_by_signal(self._context):
            raise ExternalShutdownException()

    def spin_until_future_complete(self, future: Future, timeout_sec: float | None = None) -> None:
        future.add_done_callback(lambda _f: self.wake())
        def waiting_for_it() -> bool:
            return (self._context.ok() and not future.done() and not future.cancelled()
                    and not self._is_shutdown)

        if timeout_sec is None or timeout_sec < 0:
            while waiting_for_it():
                self.spin_once_until_future_complete(future, timeout_sec)
            return
        end = time.monotonic() + timeout_sec
        left = TimeoutObject(timeout_sec)
        while waiting_for_it():
            self.spin_once_until_future_complete(future, left)
            now = time.monotonic()
            if now >= end:
                return
            left.timeout = end - now

    def spin_once(self, timeout_sec: float | None = None) -> None:
        raise NotImplementedError()

    def spin_once_until_future_complete(self, future: Future, timeout_sec: Any = None) -> None:
        raise NotImplementedError()

    # ------------------------------------------------------------------ handlers
    def _make_handler(self, entity: Any, node: Any, take: Callable[[Any], Any]) -> Task:
        entity._executor_event = True
        notify = self._notify_on_handler

        async def handler(entity: Any, is_shutdown: bool, work_tracker: _WorkTracker) -> None:
            if is_shutdown or not entity.callback_group.beginning_execution(entity):
                entity._executor_event = False
                waiting.notify()
                return
            with work_tracker:
                try:
                    call_coroutine = take(entity)
                except BaseException:
                    # A KeyboardInterrupt (Ctrl-C) in a take, which is Python here (rclpy's is C): the entity and
                    # its callback group must be served again, or every later reply or sample of it waits forever.
                    entity._executor_event = False
                    entity.callback_group.ending_execution(entity)
                    waiting.notify()
                    raise
                entity._executor_event = False
                if notify:
                    waiting.notify()
                try:
                    if call_coroutine is not None:
                        await call_coroutine()
                finally:
                    entity.callback_group.ending_execution(entity)
                    if notify:
                        waiting.notify()

        task = Task(handler, (entity, self._is_shutdown, self._work_tracker), executor=self)
        with self._tasks_lock:
            self._tasks.append((task, entity, node))
        return task

    def _take_plain(self, entity: Any) -> Any:
        return entity._take()

    def _take_client(self, client: Any) -> Any:
        return client._take(self)

    def _take_waitable(self, waitable: Any) -> Any:
        data = waitable.take_data()

        async def _execute() -> None:
            for future in waitable._futures:
                future._set_executor(self)
            await waitable.execute(data)

        return _execute

    def can_execute(self, entity: Any) -> bool:
        return not entity._executor_event and entity.callback_group.can_execute(entity)

    # ------------------------------------------------------------------ the wait
    def _wait_for_ready_callbacks(self, timeout_sec: Any = None, nodes: list[Any] | None = None,
                                  condition: Callable[[], bool] = lambda: False,
                                  ) -> Generator[tuple[Task, Any, Any], None, None]:
        timeout = _timeout_s(timeout_sec)
        deadline = None if timeout is None else time.monotonic() + timeout
        signal = waiting.SIGNAL
        yielded_work = False
        while not yielded_work and not self._is_shutdown and not condition():
            nodes_to_use = self.get_nodes() if nodes is None else nodes
            # Read before anything is looked at: a task created or an entity made ready after this (another
            # thread's create_task, a sample) has moved the generation past it, and the wait below returns at once.
            # Read after the task list, a task created in between was in neither and the executor slept past it.
            generation = signal.generation

            with self._tasks_lock:
                tasks = list(self._tasks)
            if tasks:
                for task, entity, node in reversed(tasks):
                    if not task.executing() and not task.done() and (node is None or node in nodes_to_use):
                        yielded_work = True
                        yield task, entity, node
                with self._tasks_lock:
                    self._tasks = [t for t in self._tasks if not t[0].done() and not t[0].cancelled()]

            subs: list[Any] = []
            timers: list[Any] = []
            clients: list[Any] = []
            services: list[Any] = []
            guards: list[Any] = []
            waitables: list[Any] = []
            can = self.can_execute
            for node in nodes_to_use:
                subs.extend(e for e in node._subscriptions if can(e))
                timers.extend(e for e in node._timers if can(e))
                clients.extend(e for e in node._clients if can(e))
                services.extend(e for e in node._services if can(e))
                guards.extend(e for e in node._guards if can(e))
                waitables.extend(e for e in node._waitables if can(e))
                # A user's Waitable learns of each wait (there is no rcl wait set: the argument is None).
                for e in node._joining_waitables:
                    if can(e):
                        e.add_to_wait_set(None)

            if not _any_ready(subs, timers, guards, clients, services, waitables):
                wait_s = None if deadline is None else max(0.0, deadline - time.monotonic())
                for e in (*timers, *waitables):
                    due = e._due_in_s()
                    if due is not None and (wait_s is None or due < wait_s):
                        wait_s = due
                if wait_s is None or wait_s > 0:
                    signal.wait(generation, wait_s)
            # The context first: a shutdown of the context also shuts the global executor down (its on-shutdown
            # callback), and rclpy's waiter, woken before that callback runs, reports the external shutdown.
            if not self._context.ok():
                raise ExternalShutdownException()
            if self._is_shutdown:
                raise ShutdownException()

            timers_ready = {id(e) for e in timers if e._ready()}
            subs_ready = {id(e) for e in subs if e._ready()}
            clients_ready = {id(e) for e in clients if e._ready()}
            services_ready = {id(e) for e in services if e._ready()}
            guard_ids = {id(e) for e in guards}
            waitable_ids = {id(e) for e in waitables}

            for node in nodes_to_use:
                for wt in list(node._waitables):
                    if id(wt) in waitable_ids and wt.is_ready(None) and wt.callback_group.can_execute(wt):
                        yielded_work = True
                        yield self._make_handler(wt, node, self._take_waitable), wt, node
            for node in nodes_to_use:
                for tmr in list(node._timers):
                    if id(tmr) in timers_ready and tmr._ready() and tmr.callback_group.can_execute(tmr):
                        yielded_work = True
                        yield self._make_handler(tmr, node, self._take_plain), tmr, node
                for sub in list(node._subscriptions):
                    if id(sub) in subs_ready and sub.callback_group.can_execute(sub):
                        yielded_work = True
                        yield self._make_handler(sub, node, self._take_plain), sub, node
                for gc in list(node._guards):
                    if id(gc) in guard_ids and gc._executor_triggered and gc.callback_group.can_execute(gc):
                        yielded_work = True
                        yield self._make_handler(gc, node, self._take_plain), gc, node
                for cli in list(node._clients):
                    if id(cli) in clients_ready and cli.callback_group.can_execute(cli):
                        yielded_work = True
                        yield self._make_handler(cli, node, self._take_client), cli, node
                for srv in list(node._services):
                    if id(srv) in services_ready and srv.callback_group.can_execute(srv):
                        yielded_work = True
                        yield self._make_handler(srv, node, self._take_plain), srv, node

            if timeout == 0 or (deadline is not None and time.monotonic() >= deadline):
                raise TimeoutException()
        if self._is_shutdown:
            raise ShutdownException()
        if condition():
            raise ConditionReachedException()

    def wait_for_ready_callbacks(self, *args: Any, **kwargs: Any) -> tuple[Task, Any, Any]:
        # Work found by one wait is handed out over consecutive calls with the same arguments before the
        # next wait, as rclpy's executors do; other arguments start a new wait.
        asked = (args, kwargs)
        while True:
            if self._cb_iter is None or self._cb_asked != asked:
                self._cb_asked = asked
                self._cb_iter = self._wait_for_ready_callbacks(*args, **kwargs)
            work = next(self._cb_iter, None)
            if work is not None:
                return work
            self._cb_iter = None


def _any_ready(subs: list[Any], timers: list[Any], guards: list[Any], clients: list[Any], services: list[Any],
               waitables: list[Any]) -> bool:
    return (any(e._ready() for e in subs) or any(e._ready() for e in timers) or any(e._ready() for e in guards)
            or any(e._ready() for e in clients) or any(e._ready() for e in services)
            or any(w.is_ready(None) for w in waitables))


class SingleThreadedExecutor(Executor):
    """Runs callbacks in the thread that calls spin; a callback's exception propagates out of spin."""

    def _spin_once_impl(self, timeout_sec: Any = None, wait_condition: Callable[[], bool] = lambda: False) -> None:
        try:
            handler, _entity, _node = self.wait_for_ready_callbacks(timeout_sec, None, wait_condition)
        except (ShutdownException, TimeoutException, ConditionReachedException):
            self._cb_iter = None
            return
        except BaseException:
            self._cb_iter = None
            raise
        handler()
        exc = handler.exception()
        if exc is not None:
            raise exc
        handler.result()

    def spin_once(self, timeout_sec: float | None = None) -> None:
        with _spinners:
            self._spin_once_impl(timeout_sec)

    def spin_once_until_future_complete(self, future: Future, timeout_sec: Any = None) -> None:
        future.add_done_callback(lambda _f: self.wake())
        with _spinners:
            self._spin_once_impl(timeout_sec, future.done)


class MultiThreadedExecutor(Executor):
    """Runs callbacks on a pool of `num_threads` threads (default: the CPUs this process may use)."""

    _notify_on_handler = True
    _raises_external_shutdown = False

    def __init__(self, num_threads: int | None = None, *, context: Context | None = None) -> None:
        super().__init__(context=context)
        if num_threads is None:
            num_threads = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
            num_threads = num_threads or 2
        if num_threads == 1:
            warnings.warn("MultiThreadedExecutor is used with a single thread.\n"
                          "Use the SingleThreadedExecutor instead.", stacklevel=2)
        self._futures: list[Any] = []
        self._executor = ThreadPoolExecutor(num_threads)

    def _spin_once_impl(self, timeout_sec: Any = None, wait_condition: Callable[[], bool] = lambda: False) -> None:
        try:
            handler, _entity, _node = self.wait_for_ready_callbacks(timeout_sec, None, wait_condition)
        except (ExternalShutdownException, ShutdownException, TimeoutException, ConditionReachedException):
            self._cb_iter = None
        except BaseException:
            self._cb_iter = None
            raise
        else:
            self._executor.submit(handler)
            self._futures.append(handler)
        # A finished callback is forgotten; one that raised raises here, on the spinning thread.
        for future in [f for f in self._futures if f.done()]:
            self._futures.remove(future)
            future.result()

    def spin_once(self, timeout_sec: float | None = None) -> None:
        with _spinners:
            self._spin_once_impl(timeout_sec)

    def spin_once_until_future_complete(self, future: Future, timeout_sec: Any = None) -> None:
        future.add_done_callback(lambda _f: self.wake())
        with _spinners:
            self._spin_once_impl(timeout_sec, future.done)

    def shutdown(self, timeout_sec: float | None = None) -> bool:
        ok = super().shutdown(timeout_sec)
        self._executor.shutdown(wait=True)
        return ok


for _cls in (ExternalShutdownException, ShutdownException, TimeoutException, ConditionReachedException):
    _cls.__module__ = "rclpy.executors"  # as tracebacks print them under rclpy
