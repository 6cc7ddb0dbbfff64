"""SIGINT/SIGTERM as rclpy handles them: chain to the previous handler, then shut every context down.

rclpy's C handler calls the handler that was installed before it (Python's, which raises KeyboardInterrupt
for SIGINT) and lets a thread shut the contexts down, which wakes the executors: a SingleThreadedExecutor
then raises ExternalShutdownException. Handlers go in only from the main thread, as `signal` requires.
"""

from __future__ import annotations

import enum
import signal
import threading
import weakref
from typing import Any

from diffctl.bus.session import before_close
from diffctl.client import context as _context


class SignalHandlerOptions(enum.IntEnum):
    NO = 0
    SIGINT = 1
    SIGTERM = 2
    ALL = 3

    # printed as rclpy's (a pybind11 enum) prints it, not as the bare number an IntEnum gives
    def __str__(self) -> str:
        return f"{type(self).__name__}.{self.name}"

    def __format__(self, spec: str) -> str:
        return format(str(self), spec)


_installed: dict[int, Any] = {}
_options = SignalHandlerOptions.NO


_shutdown_threads: list[threading.Thread] = []


def _join_shutdown_threads() -> None:
    """The contexts' shutdown a signal started ends before the session closes (it runs shutdown callbacks)."""
    while _shutdown_threads:
        t = _shutdown_threads.pop()
        if t is not threading.current_thread():
            t.join(2.0)


before_close(_join_shutdown_threads, first=True)


# The contexts a signal shut down: a spin loop that finds its context gone between two spin_once calls (rather
# than inside one) still reports the external shutdown, so the outcome does not depend on the scheduler.
_by_signal: weakref.WeakSet[Any] = weakref.WeakSet()


def _shutdown_all() -> None:
    for ctx in _context.all_contexts():
        if ctx.ok():
            _by_signal.add(ctx)
        ctx.try_shutdown()


def shut_down_by_signal(context: Any) -> bool:
    return context in _by_signal


def _handler(signum: int, frame: Any) -> None:
    # A thread, as rclpy's deferred one: the interrupted code may hold a context's lock.
    t = threading.Thread(target=_shutdown_all, name="rclpy-signal", daemon=True)
    _shutdown_threads.append(t)
    t.start()
    previous = _installed.get(signum)
    if callable(previous):
        previous(signum, frame)


def install_signal_handlers(options: SignalHandlerOptions = SignalHandlerOptions.ALL) -> None:
    global _options
    if threading.current_thread() is not threading.main_thread():
        return
    wanted = {
        SignalHandlerOptions.SIGINT: (signal.SIGINT,), SignalHandlerOptions.SIGTERM: (signal.SIGTERM,),
        SignalHandlerOptions.ALL: (signal.SIGINT, signal.SIGTERM), SignalHandlerOptions.NO: (),
    }[SignalHandlerOptions(options)]
    for sig in wanted:
        if sig in _installed:
            continue
        _installed[sig] = signal.signal(sig, _handler)
    _options = SignalHandlerOptions(options) if not _installed or options else _options


def get_current_signal_handlers_options() -> SignalHandlerOptions:
    has_int, has_term = signal.SIGINT in _installed, signal.SIGTERM in _installed
    if has_int and has_term:
        return SignalHandlerOptions.ALL
    if has_int:
        return SignalHandlerOptions.SIGINT
    if has_term:
        return SignalHandlerOptions.SIGTERM
    return SignalHandlerOptions.NO


def uninstall_signal_handlers() -> None:
    if threading.current_thread() is not threading.main_thread():
        return
    for sig, previous in list(_installed.items()):
        signal.signal(sig, previous if previous is not None else signal.SIG_DFL)
        del _installed[sig]
