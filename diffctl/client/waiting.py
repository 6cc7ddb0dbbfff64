"""The one wake-up signal of this process's executors: Zenoh threads, timers, guards and shutdown bump it.

rclpy waits on an rcl wait set; here every entity keeps its own ready state (a queue, a trigger flag, a
due time) and an executor sleeps on this condition until something changed or its timeout passed. A
generation counter makes "did anything change since I looked" race-free.
"""

from __future__ import annotations

import threading
import time

# Python runs signal handlers on the main thread only, between bytecodes, and the kernel hands a SIGINT/SIGTERM
# sent to the process to any thread not blocking it — one of Zenoh's or ours as well. The main thread blocked
# in a lock is not woken then, so a node could sleep through its SIGTERM (rclpy's C handler wakes its wait set
# from whatever thread it runs on). The main thread therefore waits in slices: a signal it missed is acted on
# within one.
MAIN_THREAD_SLICE_S = 0.2
_MAIN = threading.main_thread()


class WorkSignal:
    def __init__(self) -> None:
        self._cond = threading.Condition(threading.Lock())
        self._generation = 0

    @property
    def generation(self) -> int:
        return self._generation

    def notify(self) -> None:
        with self._cond:
            self._generation += 1
            self._cond.notify_all()

    def wait(self, generation: int, timeout_s: float | None) -> bool:
        """Sleep until the generation moves past `generation` (True) or `timeout_s` passes (False)."""
        with self._cond:
            if self._generation != generation:
                return True
            if timeout_s is not None and timeout_s <= 0:
                return False
            if threading.current_thread() is not _MAIN or (timeout_s is not None and timeout_s <= MAIN_THREAD_SLICE_S):
                self._cond.wait(timeout_s)
                return self._generation != generation
            deadline = None if timeout_s is None else time.monotonic() + timeout_s
            while self._generation == generation:
                left = MAIN_THREAD_SLICE_S
                if deadline is not None:
                    left = min(left, deadline - time.monotonic())
                if left <= 0:
                    return False
                self._cond.wait(left)  # returning to Python here runs any signal handler that is due
            return True


SIGNAL = WorkSignal()


def notify() -> None:
    """Something an executor may be waiting for changed (data arrived, a guard fired, a node was added)."""
    SIGNAL.notify()
