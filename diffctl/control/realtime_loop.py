"""The ros2_control_node loop: read → update → write once per tick, with its timing statistics.

A tick comes from one of two sources, as in ros2_control_node:
  WallTicker     wall clock at update_rate: a precise sleep to the next period boundary; a late cycle is an
                 overrun, counted and logged, and the missed periods are skipped (overruns.manage);
  SimClockTicker sim time from /clock (use_sim_time).
(A simulated robot's manager is stepped by the simulator itself: diffctl/sim/plugins/gz_ros2_control.py.)
"""

from __future__ import annotations

import os
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

thread_time_ns = time.thread_time_ns

# Coarse sleep until this close to the deadline, then yield-spin: time.sleep alone wakes up to ~100 µs late.
_SPIN_NS = 300_000


class Ticker(Protocol):
    def wait(self, stop: threading.Event) -> tuple[int, float] | None:
        """Block until the next cycle; (time_ns, period_s) or None when stopped / nothing to do yet."""
        ...


def configure_sched_fifo(priority: int) -> str | None:
    """Give the calling thread SCHED_FIFO at `priority`, as ros2_control_node does (thread_priority, default 50);
    None on success, else why not (no permission: the loop then runs at normal priority)."""
    if priority <= 0:
        return "thread_priority ≤ 0: real-time scheduling disabled"
    try:
        os.sched_setscheduler(threading.get_native_id(), os.SCHED_FIFO, os.sched_param(min(priority, 99)))
        return None
    except (OSError, AttributeError) as e:
        return f"Could not enable FIFO RT scheduling policy: {e}"


def sleep_until_ns(deadline_ns: int, stop: threading.Event | None = None) -> None:
    """Sleep on the monotonic clock until `deadline_ns`, precisely (coarse sleep, then a short yield-spin)."""
    while True:
        remaining = deadline_ns - time.monotonic_ns()
        if remaining <= 0:
            return
        if remaining > _SPIN_NS:
            if stop is not None and stop.is_set():
                return
            time.sleep((remaining - _SPIN_NS) / 1e9)
        else:
            time.sleep(0)


@dataclass
class LoopStats:
    """Wake-up times and per-cycle cost (ns; wall, and the loop thread's CPU time), kept for the last `capacity`
    cycles, and the overrun count."""

    capacity: int = 4096
    wakes_ns: list[int] = field(default_factory=list)
    costs_ns: list[int] = field(default_factory=list)
    cpu_ns: list[int] = field(default_factory=list)
    overruns: int = 0
    cycles: int = 0

    def reset(self, capacity: int | None = None) -> None:
        """Start a new measurement window (the loop keeps recording into the same object)."""
        if capacity is not None:
            self.capacity = capacity
        self.wakes_ns.clear()
        self.costs_ns.clear()
        self.cpu_ns.clear()
        self.overruns = 0
        self.cycles = 0

    def record(self, wake_ns: int, cost_ns: int, cpu_ns: int = 0) -> None:
        self.cycles += 1
        if len(self.wakes_ns) >= self.capacity:
            half = self.capacity // 2
            del self.wakes_ns[:half]
            del self.costs_ns[:half]
            del self.cpu_ns[:half]
        self.wakes_ns.append(wake_ns)
        self.costs_ns.append(cost_ns)
        self.cpu_ns.append(cpu_ns)

    def summary(self, period_s: float) -> dict[str, float]:
        if len(self.wakes_ns) < 2:
            return {"cycles": self.cycles, "overruns": self.overruns}
        periods = np.diff(np.asarray(self.wakes_ns, dtype=np.int64)) / 1e9
        jitter_us = np.abs(periods - period_s) * 1e6
        costs_us = np.asarray(self.costs_ns, dtype=np.float64) / 1e3
        return {
            "cycles": self.cycles,
            "overruns": self.overruns,
            "jitter_p50_us": float(np.percentile(jitter_us, 50)),
            "jitter_p99_us": float(np.percentile(jitter_us, 99)),
            "jitter_max_us": float(jitter_us.max()),
            "update_p50_us": float(np.percentile(costs_us, 50)),
            "update_p99_us": float(np.percentile(costs_us, 99)),
            "update_mean_us": float(costs_us.mean()),
            "update_cpu_mean_us": float(np.mean(self.cpu_ns)) / 1e3,
        }


class WallTicker:
    def __init__(self, update_rate: int, stats: LoopStats, warn: Callable[[str], None], manage_overruns: bool = True):
        self.period_ns = 1_000_000_000 // update_rate
        self.stats = stats
        self.warn = warn
        self.manage_overruns = manage_overruns
        self._next_ns: int | None = None
        self._prev_wall_ns: int | None = None

    def wait(self, stop: threading.Event) -> tuple[int, float] | None:
        if self._next_ns is None:
            # ros2_control_node sleeps one period before its first cycle.
            self._next_ns = time.monotonic_ns() + self.period_ns
        else:
            self._next_ns += self.period_ns
            now = time.monotonic_ns()
            if now > self._next_ns and self.manage_overruns:
                missed = (now - self._next_ns) // self.period_ns + 1
                self.stats.overruns += 1
                late_ms = (now - self._next_ns) / 1e6
                self.warn(
                    f"Overrun detected! The controller manager missed its desired rate of "
                    f"{1e9 / self.period_ns:g} Hz: the cycle ended {late_ms:.2f} ms after the next deadline "
                    f"(overruns so far: {self.stats.overruns})"
                )
                self._next_ns += missed * self.period_ns
        sleep_until_ns(self._next_ns, stop)
        if stop.is_set():
            return None
        wall = time.time_ns()
        period = self.period_ns / 1e9 if self._prev_wall_ns is None else (wall - self._prev_wall_ns) / 1e9
        self._prev_wall_ns = wall
        return wall, period


class SimClockTicker:
    """Cycles on sim time: waits until previous + period on the node's ROS clock (which follows /clock)."""

    POLL_S = 0.0005

    def __init__(self, update_rate: int, clock: object) -> None:
        self.period_ns = 1_000_000_000 // update_rate
        self.clock = clock
        self._prev: int | None = None

    def wait(self, stop: threading.Event) -> tuple[int, float] | None:
        now_ns = self.clock.now_ns  # type: ignore[attr-defined]
        if self._prev is None:
            while now_ns() == 0:  # no /clock yet
                if stop.wait(0.05):
                    return None
            self._prev = now_ns()
        while now_ns() < self._prev + self.period_ns:
            if stop.wait(self.POLL_S):
                return None
            if now_ns() < self._prev:  # the world was reset: start over
                self._prev = now_ns()
                return None
        now = now_ns()
        period = (now - self._prev) / 1e9
        self._prev = now
        return now, period


def run(
    cycle: Callable[[int, float], None],
    ticker: Ticker,
    stop: threading.Event,
    stats: LoopStats,
    on_time: Callable[[int], None] | None = None,
) -> None:
    """The real-time loop: until `stop`, wait for a tick and run one read → update → write cycle."""
    while not stop.is_set():
        tick = ticker.wait(stop)
        if tick is None:
            continue
        # The thread's CPU clock is a system call: read outside the wall-clock span, which ends before it too.
        cpu = thread_time_ns()
        wake = time.monotonic_ns()
        t_ns, period_s = tick
        if on_time is not None:
            on_time(t_ns)
        cycle(t_ns, period_s)
        stats.record(wake, time.monotonic_ns() - wake, thread_time_ns() - cpu)
