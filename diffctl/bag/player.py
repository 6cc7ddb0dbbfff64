"""The replay loop of `bag play`: messages out at their recorded pace, /clock, pause, step, loop.

Nothing here touches the bus or the terminal: messages go to `publish(topic, cdr)` and `/clock` to
`publish_clock(ns)`, the wall clock is `now_s`, and waiting is `wait(timeout_s)` (which returns early when
`wake()` is called) — so tests drive it with a fake clock. A reader thread keeps up to
`read_ahead` messages decoded from the files ahead of the player, as rosbag2's read-ahead queue does.
"""

from __future__ import annotations

import math
import queue
import threading
import time
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass

from diffctl.bag.reader import Message
from diffctl.bag.timing import PlaybackTimer, check_rate
from diffctl.errors import ConfigError

RATE_STEP = 0.1  # ↑/↓ change the rate by this much, as ros2 bag play's keys do


@dataclass(frozen=True)
class PlayOptions:
    rate: float = 1.0
    loop: bool = False
    clock_hz: float = 0.0  # 0: no /clock from the player
    start_offset_s: float = 0.0
    start_paused: bool = False
    read_ahead: int = 1000

    def __post_init__(self) -> None:
        check_rate(self.rate)
        if not math.isfinite(self.clock_hz) or self.clock_hz < 0:
            raise ConfigError(f"--clock {self.clock_hz!r} must be a positive frequency in Hz")
        if not math.isfinite(self.start_offset_s) or self.start_offset_s < 0:
            raise ConfigError(f"--start-offset {self.start_offset_s!r} must be a non-negative number of seconds")
        if self.read_ahead < 1:
            raise ConfigError(f"--read-ahead-queue-size {self.read_ahead} must be at least 1")


class _ReadAhead:
    """Messages from `source` through a bounded queue filled by a thread."""

    _END = object()

    def __init__(self, source: Iterable[Message], size: int) -> None:
        self._q: queue.Queue[object] = queue.Queue(maxsize=size)
        self._stop = threading.Event()
        self._error: BaseException | None = None
        self._thread = threading.Thread(target=self._fill, args=(iter(source),), name="bag-read-ahead",
                                        daemon=True)
        self._thread.start()

    def _fill(self, it: Iterator[Message]) -> None:
        try:
            for m in it:
                while not self._stop.is_set():
                    try:
                        self._q.put(m, timeout=0.1)
                        break
                    except queue.Full:
                        continue
                if self._stop.is_set():
                    return
        except BaseException as e:  # handed to the player's thread, which reports it
            self._error = e
        while not self._stop.is_set():
            try:
                self._q.put(self._END, timeout=0.1)
                return
            except queue.Full:
                continue

    def __iter__(self) -> Iterator[Message]:
        while True:
            item = self._q.get()
            if item is self._END:
                if self._error is not None:
                    raise self._error
                return
            yield item  # type: ignore[misc]

    def close(self) -> None:
        self._stop.set()


class Player:
    def __init__(
        self,
        messages: Callable[[int], Iterable[Message]],
        start_ns: int,
        options: PlayOptions,
        publish: Callable[[Message], None],
        publish_clock: Callable[[int], None] | None = None,
        now_s: Callable[[], float] = time.monotonic,
        sleep_s: Callable[[float], None] | None = None,
    ) -> None:
        """`messages(from_ns)` yields the bag's (selected) messages from bag time `from_ns` on; `sleep_s`
        replaces waiting on the wake-up event (a fake clock advances itself there)."""
        self._messages = messages
        self.first_ns = start_ns + round(options.start_offset_s * 1e9)
        self.options = options
        self._publish = publish
        self._publish_clock = publish_clock
        self._now_s = now_s
        self._sleep_s = sleep_s
        self.timer = PlaybackTimer(self.first_ns, options.rate, now_s, paused=options.start_paused)
        self._wake = threading.Event()
        self._stop = threading.Event()
        self._step = threading.Event()
        self._lock = threading.Lock()
        self.published = 0

    # ------------------------------------------------------------------ controls (any thread)
    def wake(self) -> None:
        self._wake.set()

    def wait(self, timeout_s: float) -> None:
        if self._sleep_s is not None:
            self._sleep_s(timeout_s)
        else:
            self._wake.wait(timeout_s)
        self._wake.clear()

    def toggle_pause(self) -> bool:
        with self._lock:
            paused = self.timer.toggle()
        self.wake()
        return paused

    def step(self) -> bool:
        """Publish the next message now (only while paused, as ros2 bag play); True if it will."""
        if not self.timer.paused:
            return False
        self._step.set()
        self.wake()
        return True

    def change_rate(self, delta: float) -> float:
        return self.set_rate(max(RATE_STEP, round(self.timer.rate + delta, 6)))

    def set_rate(self, rate: float) -> float:
        with self._lock:
            self.timer.set_rate(rate)
        self.wake()
        return rate

    def stop(self) -> None:
        self._stop.set()
        self.wake()

    # ------------------------------------------------------------------ the loop
    def run(self) -> int:
        """Play until the end (or forever with loop) or stop(); returns how many messages went out."""
        clock = None
        if self._publish_clock is not None and self.options.clock_hz > 0:
            clock = threading.Thread(target=self._clock_loop, name="bag-clock", daemon=True)
            clock.start()
        try:
            while not self._stop.is_set():
                with self._lock:
                    self.timer.jump_to(self.first_ns)
                before = self.published
                self._play_once()
                if not self.options.loop or self.published == before:
                    break  # looping over nothing (an offset past the end) would spin
        finally:
            self._stop.set()
            if clock is not None:
                clock.join(2.0)
        return self.published

    def _play_once(self) -> None:
        source = _ReadAhead(self._messages(self.first_ns), self.options.read_ahead)
        try:
            for msg in source:
                if not self._due(msg):
                    return
                self._publish(msg)
                self.published += 1
        finally:
            source.close()

    def _due(self, msg: Message) -> bool:
        """Wait until `msg` is due (or stepped to); False when stopped."""
        while not self._stop.is_set():
            if self._step.is_set():
                self._step.clear()
                with self._lock:
                    self.timer.jump_to(msg.log_time_ns)
                return True
            with self._lock:
                dt = self.timer.wall_at(msg.log_time_ns) - self._now_s()
            if dt <= 0:
                return True
            self.wait(min(dt, 0.25))
        return False

    def _clock_loop(self) -> None:
        assert self._publish_clock is not None
        period = 1.0 / self.options.clock_hz
        while not self._stop.is_set():
            with self._lock:
                now_ns = self.timer.bag_now_ns()
            self._publish_clock(now_ns)
            self._stop.wait(period)
