"""realtime_tools' RealtimePublisher: controllers publish from the control loop without waiting on the network.

A controller's `publish(msg)` serializes the message on the calling (real-time) thread — controllers reuse
their message objects from cycle to cycle, so the bytes must be taken now — and hands them to one publishing
thread per process, which does the Zenoh put (the costly part: ~100 µs and more on a busy machine). Samples of
one publisher leave in order. When the publishing thread falls far behind, the oldest waiting samples are
dropped and counted, as realtime_tools skips a cycle whose previous message is still being sent.
"""

from __future__ import annotations

import collections
import threading
from typing import Any

from diffctl.bus import types

# Waiting samples across all publishers of the process before the oldest are dropped: generous, since a put is
# fast when the machine is not starved and a burst (start-up, a stall) should not lose data.
CAPACITY = 1024


class PublishingThread:
    """Puts queued samples on the bus, in order, off the control loop's thread."""

    def __init__(self, capacity: int = CAPACITY) -> None:
        self._queue: collections.deque[tuple[Any, bytes]] = collections.deque()
        self._capacity = capacity
        self._wake = threading.Condition()
        self.dropped = 0
        self._thread = threading.Thread(target=self._run, name="realtime_publisher", daemon=True)
        self._thread.start()

    def submit(self, publisher: Any, cdr: bytes) -> None:
        with self._wake:
            if len(self._queue) >= self._capacity:
                self._queue.popleft()
                self.dropped += 1
            self._queue.append((publisher, cdr))
            self._wake.notify()

    def _run(self) -> None:
        while True:
            with self._wake:
                while not self._queue:
                    self._wake.wait()
                publisher, cdr = self._queue.popleft()
            if getattr(publisher, "closed", False):
                continue
            try:
                publisher.publish_raw(cdr)
            except Exception:  # a publisher closed meanwhile (controller unloaded, shutdown): nothing to send to
                pass

    def flush(self, timeout_s: float = 1.0) -> bool:
        """Wait until everything queued so far has been put (tests, shutdown)."""
        done = threading.Event()
        marker = _Marker(done)
        with self._wake:
            self._queue.append((marker, b""))
            self._wake.notify()
        return done.wait(timeout_s)


class _Marker:
    def __init__(self, done: threading.Event) -> None:
        self._done = done

    def publish_raw(self, _cdr: bytes) -> None:
        self._done.set()


_thread: PublishingThread | None = None
_lock = threading.Lock()


def publishing_thread() -> PublishingThread:
    global _thread
    with _lock:
        if _thread is None:
            _thread = PublishingThread()
        return _thread


class RealtimePublisher:
    """A bus publisher whose `publish` returns as soon as the message is serialized."""

    def __init__(self, publisher: Any, thread: PublishingThread | None = None) -> None:
        self._pub = publisher
        self._thread = thread or publishing_thread()

    def publish(self, msg: Any) -> None:
        if isinstance(msg, dict):
            msg = types.new(self._pub.type, msg)
        self._thread.submit(self._pub, types.serialize(msg, self._pub.type))

    def close(self) -> None:
        self._pub.close()

    def __getattr__(self, item: str) -> Any:
        # topic, type, subscription_count, matching, … are the wrapped publisher's
        return getattr(self._pub, item)
