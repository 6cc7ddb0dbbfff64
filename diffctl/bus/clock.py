"""Node time: wall clock, or sim time from /clock when `use_sim_time` is set; timers on either."""

from __future__ import annotations

import threading
import time
import weakref
from collections.abc import Callable
from typing import Any

from diffctl.bus.session import before_close


class Clock:
    def __init__(self, use_sim_time: bool = False) -> None:
        self.use_sim_time = use_sim_time
        self._sim_ns = 0
        self._cond = threading.Condition()

    def on_clock(self, msg: Any) -> None:
        ns = int(msg.clock.sec) * 1_000_000_000 + int(msg.clock.nanosec)
        with self._cond:
            # /clock going backwards means the world was reset: follow it, as ROS time does.
            self._sim_ns = ns
            self._cond.notify_all()

    def set_sim_ns(self, ns: int) -> None:
        """Sim time from the simulator itself (a node hosted inside it needs no /clock round trip)."""
        with self._cond:
            self._sim_ns = ns
            self._cond.notify_all()

    @property
    def started(self) -> bool:
        return not self.use_sim_time or self._sim_ns > 0

    def now_ns(self) -> int:
        return self._sim_ns if self.use_sim_time else time.time_ns()

    def sleep_until(self, t_ns: int, stop: threading.Event) -> bool:
        """Sleep until this clock reaches t_ns; False when `stop` was set first."""
        if not self.use_sim_time:
            while not stop.is_set():
                remaining = (t_ns - time.time_ns()) / 1e9
                if remaining <= 0:
                    return True
                stop.wait(min(remaining, 0.1))
            return False
        with self._cond:
            while not stop.is_set() and self._sim_ns < t_ns:
                self._cond.wait(0.1)
        return not stop.is_set()


_live_timers: weakref.WeakSet[Timer] = weakref.WeakSet()


def _stop_timers() -> None:
    for t in list(_live_timers):
        t.cancel(join_s=1.0)


before_close(_stop_timers)


class Timer:
    """Calls `callback()` every `period_s` of the clock, on its own thread, without drift."""

    def __init__(self, clock: Clock, period_s: float, callback: Callable[[], None], on_error: Callable[[str], None]):
        if not period_s > 0:
            raise ValueError(f"timer period must be > 0 s, got {period_s!r}")
        self._clock = clock
        self._period_ns = int(period_s * 1e9)
        self._callback = callback
        self._on_error = on_error
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True, name="timer")
        _live_timers.add(self)
        self._thread.start()

    def _run(self) -> None:
        nxt = self._clock.now_ns() + self._period_ns
        while self._clock.sleep_until(nxt, self._stop):
            try:
                self._callback()
            except Exception as e:
                self._on_error(f"timer callback raised {type(e).__name__}: {e}")
            now = self._clock.now_ns()
            nxt += self._period_ns
            if nxt < now - self._period_ns or nxt > now + 10 * self._period_ns:
                nxt = now + self._period_ns  # fell far behind, or time jumped back: resynchronise

    def cancel(self, join_s: float = 0.0) -> None:
        self._stop.set()
        if join_s > 0 and self._thread is not threading.current_thread():
            self._thread.join(join_s)
