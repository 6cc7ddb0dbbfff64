"""realtime_tools' RealtimePublisher: controllers publish from the control loop without waiting on the network.

A controller's `publish(msg)` serializes the message on the calling (real-time) thread — controllers reuse
their message objects from cycle to cycle, so the bytes must be taken now — and hands them to one publishing
thread per process, which does the Zenoh put (the costly part: ~100 µs and more on a busy machine). A
controller that publishes from a CDR template (`publish_values(template, values)`) hands over the values
instead, already a snapshot, and the publishing thread packs them (as realtime_tools copies the message in the
loop and serializes it in its publishing thread). Samples of one publisher leave in order. When the
publishing thread falls far behind, the oldest waiting samples are dropped and counted, as realtime_tools
skips a cycle whose previous message is still being sent.

While the controller manager runs its controllers (`hold()` … `release()`, once per cycle), samples are
queued without waking the publishing thread; `release` wakes it once, after the controllers ran, instead of
once per message in the middle of them, where it would take the GIL (and the CPU) from the loop. Samples
from any other thread wake it at once. With `poll_held(True)` (the wall-clock control loop of
ros2_control_node), the control thread does not wake it at all: once held cycles hand samples over, the
publishing thread polls the queue, as realtime_tools' publishing loop polls its message, until none has come
for IDLE_NS — the wake-up, a futex system call of ~15-20 µs on a cold cycle, is then no part of the real-time
cycle. It sleeps through most of the period the batches come at and looks every POLL_S from LEAD_NS before
the next is due (looking every POLL_S throughout cost 6 % of a core at 100 Hz).

The publisher wrapped is a client (rclpy-API) Publisher, as `get_node().create_publisher(…)` returns it.
"""

from __future__ import annotations

import collections
import functools
import threading
import time
from collections.abc import Sequence
from threading import get_ident as _get_ident
from typing import Any

# Waiting samples across all publishers of the process before the oldest are dropped: generous, since a put is
# fast when the machine is not starved and a burst (start-up, a stall) should not lose data.
CAPACITY = 1024
POLL_S = 0.0005  # realtime_tools' publishing loop sleeps this long between looks at its message
IDLE_NS = 100_000_000  # polling stops when held cycles have handed nothing over for this long
LEAD_NS = 1_000_000  # polling starts this long before the next batch is due (by the gap between the last two)


class PublishingThread:
    """Puts queued samples on the bus, in order, off the control loop's thread."""

    def __init__(self, capacity: int = CAPACITY) -> None:
        # (publisher, template or None, its leaf values or the serialized bytes)
        self._queue: collections.deque[tuple[Any, Any, Any]] = collections.deque()
        self._capacity = capacity
        # A binary semaphore: unlocked = "samples may be waiting". A plain lock rather than a Condition, whose
        # notify is Python code that the control loop would run (cold) every cycle; deque operations are atomic.
        self._signal = threading.Lock()
        self._signal.acquire()
        self.dropped = 0
        self._holder: int | None = None  # the thread whose samples wait for its release()
        self.poll_held = False  # poll for held cycles' samples instead of being woken by release()
        self._polling = False  # polling now: release() leaves the samples to the next look
        self._thread = threading.Thread(target=self._run, name="realtime_publisher", daemon=True)
        self._thread.start()

    def submit(self, publisher: Any, template: Any, data: Any) -> None:
        """Queue bytes (`template` None) or a CdrTemplate and the leaf values it is to be packed with."""
        queue = self._queue
        queue.append((publisher, template, data))
        if len(queue) > self._capacity:
            self._drop_oldest()
        if self._holder != _get_ident():  # the holding thread wakes it once, at release()
            self._wake()

    def _drop_oldest(self) -> None:
        queue = self._queue
        excess = len(queue) - self._capacity
        while excess > 0:  # fallen far behind: the oldest go
            try:
                queue.popleft()
            except IndexError:
                break
            self.dropped += 1
            excess -= 1

    def _wake(self) -> None:
        try:
            self._signal.release()
        except RuntimeError:  # already signalled, not yet taken
            pass

    def _run(self) -> None:
        queue = self._queue
        idle_since: int | None = None  # polling: since when no sample has been found
        found_ns = 0  # polling: when the last batch of samples was found
        gap_ns = 0  # polling: the time between the last two batches (the control period, give or take a look)
        while True:
            if queue and not (self._polling and self._holder is not None):  # polling: never in the middle of a cycle
                if idle_since is not None:  # a new batch
                    now = time.monotonic_ns()
                    gap_ns = now - found_ns if now - found_ns < IDLE_NS else 0
                    found_ns = now
                    idle_since = None
                try:
                    publisher, template, data = queue.popleft()
                except IndexError:
                    continue
                try:
                    publisher.publish(data if template is None else template.encode(data))
                except Exception:  # a publisher closed meanwhile (controller unloaded, shutdown): nowhere to send
                    pass
                continue
            if self._polling:
                now = time.monotonic_ns()
                if idle_since is None:
                    idle_since = now
                if now - idle_since < IDLE_NS or self._holder is not None:
                    # Asleep through most of the period the batches come at, then a look every POLL_S; a sample
                    # from another thread than the cycle's signals, and ends the wait at once.
                    ahead_ns = found_ns + gap_ns - LEAD_NS - now
                    self._signal.acquire(timeout=ahead_ns / 1e9 if ahead_ns > POLL_S * 1e9 else POLL_S)
                    continue
                self._polling = False  # a release from now on wakes this thread
                if queue:
                    continue
            idle_since = None
            self._signal.acquire()  # until a producer appends and signals (or signalled meanwhile)

    def flush(self, timeout_s: float = 1.0) -> bool:
        """Wait until everything queued so far has been put (tests, shutdown)."""
        done = threading.Event()
        self._queue.append((_Marker(done), None, b""))
        self._wake()
        return done.wait(timeout_s)


class _Marker:
    def __init__(self, done: threading.Event) -> None:
        self._done = done

    def publish(self, _cdr: bytes) -> None:
        self._done.set()


def hold() -> PublishingThread | None:
    """Queue this thread's samples without waking the process's publishing thread until `release(…)` of
    the value returned (None: nothing to hold, or held already). Plain functions, not a context manager:
    this runs on every control cycle."""
    t = _thread
    if t is None or t._holder is not None:
        return None
    t._holder = _get_ident()
    return t


def release(t: PublishingThread | None) -> None:
    """End a `hold`: wake the publishing thread if samples wait."""
    if t is None:
        return
    t._holder = None
    if t._queue and not t._polling:
        t._polling = t.poll_held  # when it polls, the following cycles need not wake it
        try:
            t._signal.release()  # _wake(), without its frame: this runs on every control cycle
        except RuntimeError:  # already signalled, not yet taken
            pass


_thread: PublishingThread | None = None
_lock = threading.Lock()


def poll_held(on: bool) -> None:
    """Let the process's publishing thread poll for held cycles' samples (True) or be woken by `release`."""
    publishing_thread().poll_held = on


def publishing_thread() -> PublishingThread:
    global _thread
    with _lock:
        if _thread is None:
            _thread = PublishingThread()
        return _thread


class RealtimePublisher:
    """realtime_tools::RealtimePublisher: wraps a client Publisher; `publish` returns once the message is
    serialized (`msg_type`, `topic_name`, `get_subscription_count()` … are the wrapped publisher's)."""

    def __init__(self, publisher: Any, thread: PublishingThread | None = None) -> None:
        from diffctl.client.interfaces import serialize

        self.publisher = publisher
        self._thread = thread or publishing_thread()
        self._serialize = serialize
        # publish_values(template, values) is thread.submit(publisher, template, values): bound here so a
        # cycle's call is one frame, not two.
        self.publish_values = functools.partial(self._thread.submit, publisher)

    def publish(self, msg: Any) -> None:
        self._thread.submit(self.publisher, None, self._serialize(msg))

    def publish_values(self, template: Any, values: Sequence[Any]) -> None:
        """Publish the message `template` (a CdrTemplate) describes with its leaves set to `values`, which
        must not change afterwards (a fresh list or tuple); packed on the publishing thread. (Replaced per
        instance by a partial of the thread's submit, which does the same.)"""
        self._thread.submit(self.publisher, template, values)

    def __getattr__(self, item: str) -> Any:
        return getattr(self.publisher, item)
