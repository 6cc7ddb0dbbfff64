"""Ending a command-line tool's loop on Ctrl-C or SIGTERM (echo, pub, hz, bag record and play, the router).

Python runs signal handlers on the main thread only, between bytecodes, and the kernel may hand a signal sent
to the process to any of its threads (Zenoh's among them); a main thread blocked in an untimed wait is then
not woken and the tool never stops. The stop event's untimed wait on the main thread therefore wakes in
slices, and a signal another thread took is acted on within one.
"""

from __future__ import annotations

import signal
import threading

MAIN_THREAD_SLICE_S = 0.2


class StopEvent(threading.Event):
    """A threading.Event whose untimed `wait()` on the main thread lets due signal handlers run."""

    def wait(self, timeout: float | None = None) -> bool:
        if timeout is not None or threading.current_thread() is not threading.main_thread():
            return super().wait(timeout)
        while not super().wait(MAIN_THREAD_SLICE_S):
            pass
        return True


def stop_on_signals(*extra: signal.Signals) -> StopEvent:
    """An event that SIGINT or SIGTERM (and `extra`) sets: the tool finishes its loop, closes what it wrote,
    and exits 0."""
    stop = StopEvent()
    for sig in (signal.SIGINT, signal.SIGTERM, *extra):
        signal.signal(sig, lambda *_: stop.set())
    return stop
