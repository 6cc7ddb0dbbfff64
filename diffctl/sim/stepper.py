"""The simulation loop: fixed physics steps, sim-time tasks, run/pause/step, real-time factor pacing.

One thread (the sim thread) owns PyBullet. Other threads (Zenoh callbacks) hand work over with
`call_soon`, which runs between two steps. Periodic work (sensors, clock, odometry, controller
manager cycles) is a `Task` run right after the step that reaches its due time, on sim time, so what it sees
never depends on machine speed. Per-step cost is kept to a counter compare when no task is due:
1 ms steps at 50x real time leave well under 20 µs per step for everything.
"""

from __future__ import annotations

import collections
import heapq
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field

# Behind real time by more than this (a slow machine, a long task), pacing restarts from now instead of
# bursting to catch up.
MAX_LAG_S = 0.2
# Sleep only when at least this far ahead: shorter sleeps cost more than they pace.
MIN_SLEEP_S = 0.001
IDLE_WAIT_S = 0.05


class Task:
    __slots__ = ("fn", "live", "name", "next_ns", "period_ns", "seq")

    def __init__(self, name: str, period_ns: int, fn: Callable[[int], None], next_ns: int, seq: int) -> None:
        self.name = name
        self.period_ns = max(1, int(period_ns))
        self.fn = fn
        self.next_ns = next_ns
        self.seq = seq  # ties run in the order tasks were added
        self.live = True


@dataclass
class LoopStats:
    """Counters the stats topic reports, read by the sim thread only."""

    iterations: int = 0
    wall_start_s: float = field(default_factory=time.perf_counter)
    idle_s: float = 0.0  # sleeping for pacing or paused


class Stepper:
    def __init__(self, step: Callable[[], None], step_ns: int, *, rtf: float = 1.0, paused: bool = True) -> None:
        self._step = step
        self.step_ns = step_ns
        self.sim_time_ns = 0
        self.rtf = rtf
        self.paused = paused
        self.stats = LoopStats()
        self.tasks: list[Task] = []
        self.step_hooks: list[Callable[[], None]] = []
        self.idle_hooks: list[Callable[[], None]] = []
        # Around each batch of due tasks: the outbox holds its wake-up until the batch has queued everything.
        self.batch_hooks: list[tuple[Callable[[], None], Callable[[], None]]] = []
        self._inbox: collections.deque[Callable[[], None]] = collections.deque()
        self._wake = threading.Event()
        self._pending_steps = 0
        self._step_waiters: list[Callable[[], None]] = []
        self._next_due = 1 << 62
        self._heap: list[tuple[int, int, Task]] = []
        self._seq = 0
        self._anchor: tuple[float, int] | None = None

    # --- from any thread -----------------------------------------------------------------------------

    def call_soon(self, fn: Callable[[], None]) -> None:
        """Run `fn` on the sim thread between two steps (or while paused)."""
        self._inbox.append(fn)
        self._wake.set()

    # --- sim thread ----------------------------------------------------------------------------------

    def add_task(
        self,
        name: str,
        period_ns: int,
        fn: Callable[[int], None],
        *,
        first_ns: int | None = None,
        before_others: bool = False,
    ) -> Task:
        """Run `fn(sim_time_ns)` every `period_ns` of sim time from `first_ns` (default: now); tasks due at
        the same time run in the order they were added, `before_others` ones first."""
        self._seq += 1
        seq = -self._seq if before_others else self._seq
        task = Task(name, period_ns, fn, self.sim_time_ns if first_ns is None else first_ns, seq)
        self.tasks.append(task)
        heapq.heappush(self._heap, (task.next_ns, task.seq, task))
        self._next_due = self._heap[0][0]
        return task

    def remove_task(self, task: Task) -> None:
        if task in self.tasks:
            self.tasks.remove(task)
            task.live = False  # its heap entry is dropped when it comes up

    def set_paused(self, paused: bool) -> None:
        self.paused = paused
        self._pending_steps = 0
        self._anchor = None
        # A step request cut short by pause/resume is answered now rather than never.
        waiters, self._step_waiters = self._step_waiters, []
        for w in waiters:
            w()

    def set_rtf(self, rtf: float) -> None:
        self.rtf = rtf
        self._anchor = None

    def step_n(self, n: int, done: Callable[[], None] | None = None) -> None:
        """While paused, run `n` steps, then call `done` (e.g. to answer the request)."""
        self._pending_steps += n
        if done is not None:
            self._step_waiters.append(done)

    def reset_time(self) -> None:
        """Back to sim time 0 and iteration 0 (as Gazebo's reset); every task becomes due at once."""
        self.sim_time_ns = 0
        self.stats.iterations = 0
        for t in self.tasks:
            t.next_ns = 0
        self.reschedule()
        self._anchor = None

    def run_due(self) -> None:
        """Run every task due at the current sim time, each rescheduled on its period grid."""
        now = self.sim_time_ns
        heap = self._heap
        due = []
        while heap and heap[0][0] <= now:
            due.append(heapq.heappop(heap)[2])
        for begin, _ in self.batch_hooks:
            begin()
        try:
            self._run_tasks(due, now)
        finally:
            for _, end in self.batch_hooks:
                end()
        while heap and not heap[0][2].live:
            heapq.heappop(heap)
        self._next_due = heap[0][0] if heap else 1 << 62

    def _run_tasks(self, due: list[Task], now: int) -> None:
        heap = self._heap
        for task in due:
            if not task.live:
                continue
            task.fn(now)
            if not task.live:  # removed by its own run
                continue
            # Stay on the period grid; after a long pause or a reset skip what was missed.
            task.next_ns += task.period_ns
            if task.next_ns <= now:
                task.next_ns = now + task.period_ns
            heapq.heappush(heap, (task.next_ns, task.seq, task))

    def reschedule(self) -> None:
        """Rebuild the schedule from the tasks' due times (after they were changed wholesale)."""
        self._heap = [(t.next_ns, t.seq, t) for t in self.tasks]
        heapq.heapify(self._heap)
        self._next_due = self._heap[0][0] if self._heap else 1 << 62

    def drain(self) -> None:
        while self._inbox:
            self._inbox.popleft()()

    def run(self, stop: threading.Event) -> None:
        """The loop; returns when `stop` is set."""
        self.drain()
        self.run_due()
        step, step_ns, hooks, inbox = self._step, self.step_ns, self.step_hooks, self._inbox
        perf = time.perf_counter
        while not stop.is_set():
            if inbox:
                self.drain()
            if self.paused and self._pending_steps == 0:
                t0 = perf()
                self._wake.wait(IDLE_WAIT_S)
                self._wake.clear()
                self.stats.idle_s += perf() - t0
                for h in self.idle_hooks:
                    h()
                continue
            for h in hooks:
                h()
            step()
            self.sim_time_ns += step_ns
            self.stats.iterations += 1
            if self.sim_time_ns >= self._next_due:
                self.run_due()
            if self._pending_steps:
                self._pending_steps -= 1
                if self._pending_steps == 0:
                    waiters, self._step_waiters = self._step_waiters, []
                    for w in waiters:
                        w()
                continue
            if self.rtf > 0:
                self._pace(perf)

    def _pace(self, perf: Callable[[], float]) -> None:
        now = perf()
        if self._anchor is None:
            self._anchor = (now, self.sim_time_ns)
            return
        wall0, sim0 = self._anchor
        ahead = wall0 + (self.sim_time_ns - sim0) * 1e-9 / self.rtf - now
        if ahead > MIN_SLEEP_S:
            time.sleep(ahead)
            self.stats.idle_s += perf() - now
        elif ahead < -MAX_LAG_S:
            self._anchor = (now, self.sim_time_ns)
