"""rclpy.task: Future (not asyncio's) and Task, which runs a function or steps a coroutine.

As Jazzy's current release (7.1.6): a future is pending, cancelled or finished; `done()` means finished.
Semantics users rely on: `result()` is None while pending and raises a stored exception; `await future`
yields until it is done; done callbacks become executor tasks when the future knows its executor, else
run at once; an exception nobody fetched is printed when the future is collected.
"""

from __future__ import annotations

import enum
import inspect
import sys
import threading
import warnings
import weakref
from collections.abc import Callable, Generator
from typing import Any


def _no_executor() -> None:
    return None


class _Unfetched:
    """The exception a future holds until somebody fetches it."""

    __slots__ = ("exception",)

    def __init__(self, exception: BaseException) -> None:
        self.exception: BaseException | None = exception


def _report_unfetched(box: _Unfetched) -> None:
    if box.exception is not None:
        print("The following exception was never retrieved: " + str(box.exception), file=sys.stderr)


class FutureState(enum.Enum):
    PENDING = "PENDING"
    CANCELLED = "CANCELLED"
    FINISHED = "FINISHED"


class Future:
    def __init__(self, *, executor: Any = None) -> None:
        self._state = FutureState.PENDING
        self._result: Any = None
        self._exception: BaseException | None = None
        self._unfetched: _Unfetched | None = None
        self._callbacks: list[Callable[[Future], None]] = []
        self._lock = threading.Lock()
        self._executor: Callable[[], Any] = _no_executor
        self._set_executor(executor)

    def __await__(self) -> Generator[None, None, Any]:
        while self._state is FutureState.PENDING:
            yield
        return self.result()

    def _pending(self) -> bool:
        return self._state is FutureState.PENDING

    def cancel(self) -> None:
        with self._lock:
            if self._state is not FutureState.PENDING:
                return
            self._state = FutureState.CANCELLED
        self._schedule_or_invoke_done_callbacks()

    def cancelled(self) -> bool:
        return self._state is FutureState.CANCELLED

    def done(self) -> bool:
        return self._state is FutureState.FINISHED

    def result(self) -> Any:
        exc = self.exception()
        if exc:
            raise exc
        return self._result

    def exception(self) -> BaseException | None:
        if self._unfetched is not None:
            self._unfetched.exception = None
        return self._exception

    def set_result(self, result: Any) -> None:
        with self._lock:
            self._result = result
            self._state = FutureState.FINISHED
        self._schedule_or_invoke_done_callbacks()

    def set_exception(self, exception: BaseException) -> None:
        with self._lock:
            self._exception = exception
            self._unfetched = _Unfetched(exception)
            # A finalizer only for a future that holds an exception, not a __del__ on every future: each callback
            # is a Task, and a SIGINT handled inside a __del__ loses its KeyboardInterrupt ("Exception ignored").
            # Also at exit, where rclpy's __del__ reports the tasks its executor still holds (an action's
            # execute task that failed after Ctrl-C)
            weakref.finalize(self, _report_unfetched, self._unfetched)
            self._state = FutureState.FINISHED
        self._schedule_or_invoke_done_callbacks()

    def _schedule_or_invoke_done_callbacks(self) -> None:
        with self._lock:
            executor = self._executor()
            callbacks, self._callbacks = self._callbacks, []
        if executor is not None:
            for cb in callbacks:
                executor.create_task(cb, self)
            return
        for cb in callbacks:
            try:
                cb(self)
            except Exception as e:  # one bad callback must not keep the others from running
                warnings.warn(f"Unhandled exception in done callback: {e}", stacklevel=2)

    def _set_executor(self, executor: Any) -> None:
        with self._lock:
            self._executor = _no_executor if executor is None else weakref.ref(executor)

    def add_done_callback(self, callback: Callable[[Future], None]) -> None:
        # Added to a settled future, it runs now: as a task of the future's executor if it has one, else here,
        # outside the lock (the callback may well use this future).
        with self._lock:
            if self._state is FutureState.PENDING:
                self._callbacks.append(callback)
                return
            executor = self._executor()
            if executor is not None:
                executor.create_task(callback, self)
                return
        callback(self)

    def remove_done_callback(self, callback: Callable[[Future], None]) -> bool:
        """Forget a done callback; False if it was not there (or the future completed already)."""
        with self._lock:
            try:
                self._callbacks.remove(callback)
            except ValueError:
                return False
            return True


class Task(Future):
    """A function or coroutine run by an executor; its outcome is this future's."""

    def __init__(self, handler: Callable[..., Any], args: Any = None, kwargs: Any = None,
                 executor: Any = None) -> None:
        super().__init__(executor=executor)
        self._handler: Any = handler
        self._args = list(args) if args is not None else []
        self._kwargs = dict(kwargs) if kwargs is not None else {}
        if inspect.iscoroutinefunction(handler):
            self._handler = handler(*self._args, **self._kwargs)
            self._args, self._kwargs = [], {}
        self._executing = False
        self._task_lock = threading.Lock()

    def __call__(self) -> None:
        """Run the function, or step the coroutine once (it resumes at the next call)."""
        if not self._pending() or self._executing or not self._task_lock.acquire(blocking=False):
            return
        try:
            if self._pending():
                self._executing = True
                self._step()
                self._executing = False
        finally:
            self._task_lock.release()

    def _step(self) -> None:
        handler = self._handler
        try:
            if inspect.iscoroutine(handler):
                try:
                    handler.send(None)
                    return  # it awaits something: pending until a later call resumes it
                except StopIteration as returned:
                    outcome = returned.value
            else:
                outcome = handler(*self._args, **self._kwargs)
        except Exception as e:
            self.set_exception(e)
        else:
            self.set_result(outcome)
        self._complete()

    def _complete(self) -> None:
        self._handler = None
        self._args, self._kwargs = [], {}

    def executing(self) -> bool:
        return self._executing

    def cancel(self) -> None:
        if self._pending() and inspect.iscoroutine(self._handler):
            self._handler.close()
        super().cancel()
