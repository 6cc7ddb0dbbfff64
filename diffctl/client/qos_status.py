"""The QoS statuses DDS keeps and rmw_zenoh does not: missed deadlines, lost and changed liveliness.

Pure bookkeeping on steady-clock nanoseconds handed in by the caller; `qos_events.py` feeds it from the wire and
the executor reads it. Each status counts the way Fast DDS (the Jazzy wheels' middleware) was observed to:

* a deadline counts one miss per whole period without a sample (a write for a publisher, an arrival for a
  subscription), from the first one on, for as long as the endpoint lives;
* a MANUAL_BY_TOPIC publisher loses its liveliness once per lease without an assertion (a write or
  `assert_liveliness()`), from its first assertion on;
* a subscription counts the publishers it hears with a finite lease: alive from their first assertion, not
  alive once a MANUAL_BY_TOPIC publisher's lease runs out, gone when the publisher goes (an AUTOMATIC publisher
  stays alive for as long as it exists, as DDS's participant asserts it).

Every status is read as rmw's: totals and the change since the previous read.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass


class MissedDeadlines:
    """Periods of `period_ns` that passed without a `hit()`."""

    def __init__(self, period_ns: int) -> None:
        self.period_ns = period_ns
        self._last_ns: int | None = None
        self._folded = 0  # misses of the gaps that a hit already closed
        self._read = 0
        self._lock = threading.Lock()

    def hit(self, now_ns: int) -> None:
        with self._lock:
            if self._last_ns is not None:
                self._folded += (now_ns - self._last_ns) // self.period_ns
            self._last_ns = now_ns

    def total(self, now_ns: int) -> int:
        last = self._last_ns
        return self._folded if last is None else self._folded + (now_ns - last) // self.period_ns

    def pending(self, now_ns: int) -> bool:
        return self.total(now_ns) > self._read

    def read(self, now_ns: int) -> tuple[int, int]:
        """(total_count, total_count_change) since the previous read."""
        with self._lock:
            total = self.total(now_ns)
            change, self._read = total - self._read, total
            return total, change

    def due_in_ns(self, now_ns: int) -> int | None:
        """Until the next miss, or None while nothing has started the clock."""
        last = self._last_ns
        if last is None:
            return None
        return self.period_ns - (now_ns - last) % self.period_ns


class LostLiveliness:
    """A MANUAL_BY_TOPIC publisher's own view: a lease of `lease_ns` that ran out after an assertion."""

    def __init__(self, lease_ns: int) -> None:
        self.lease_ns = lease_ns
        self._asserted_ns: int | None = None
        self._lost = 0
        self._read = 0
        self._lock = threading.Lock()

    def assert_alive(self, now_ns: int) -> None:
        with self._lock:
            self._expire(now_ns)
            self._asserted_ns = now_ns

    def _expire(self, now_ns: int) -> None:
        if self._asserted_ns is not None and now_ns - self._asserted_ns > self.lease_ns:
            self._asserted_ns = None
            self._lost += 1

    def pending(self, now_ns: int) -> bool:
        with self._lock:
            self._expire(now_ns)
            return self._lost > self._read

    def read(self, now_ns: int) -> tuple[int, int]:
        with self._lock:
            self._expire(now_ns)
            change, self._read = self._lost - self._read, self._lost
            return self._lost, change

    def due_in_ns(self, now_ns: int) -> int | None:
        asserted = self._asserted_ns
        return None if asserted is None else max(0, asserted + self.lease_ns - now_ns + 1)


_HEARD_NOTHING, _ALIVE, _NOT_ALIVE = 0, 1, 2


@dataclass
class _Writer:
    lease_ns: int
    manual: bool
    state: int = _HEARD_NOTHING
    asserted_ns: int = 0


class ChangedLiveliness:
    """A subscription's view of the publishers it hears, by GID."""

    def __init__(self) -> None:
        self._writers: dict[bytes, _Writer] = {}
        self.alive = 0
        self.not_alive = 0
        self._alive_change = 0
        self._not_alive_change = 0
        self._lock = threading.Lock()

    def _move(self, w: _Writer, state: int) -> None:
        for s, sign in ((w.state, -1), (state, 1)):
            if s == _ALIVE:
                self.alive += sign
                self._alive_change += sign
            elif s == _NOT_ALIVE:
                self.not_alive += sign
                self._not_alive_change += sign
        w.state = state

    def writer(self, gid: bytes, lease_ns: int | None, manual: bool) -> None:
        """A publisher of the topic appeared; only one with a finite lease is watched."""
        if lease_ns is not None:
            with self._lock:
                self._writers.setdefault(gid, _Writer(lease_ns, manual))

    def asserted(self, gid: bytes, now_ns: int) -> bool:
        """A sample or an explicit assertion from `gid`; False if that publisher is not known (yet)."""
        w = self._writers.get(gid)
        if w is None:
            return False
        with self._lock:
            w.asserted_ns = now_ns
            if w.state != _ALIVE:
                self._move(w, _ALIVE)
        return True

    def knows(self, gid: bytes) -> bool:
        return gid in self._writers

    def gone(self, gid: bytes) -> None:
        with self._lock:
            w = self._writers.pop(gid, None)
            if w is not None and w.state != _HEARD_NOTHING:
                self._move(w, _HEARD_NOTHING)

    def _expire(self, now_ns: int) -> None:
        for w in self._writers.values():
            if w.state == _ALIVE and w.manual and now_ns - w.asserted_ns > w.lease_ns:
                self._move(w, _NOT_ALIVE)

    def pending(self, now_ns: int) -> bool:
        with self._lock:
            self._expire(now_ns)
            return bool(self._alive_change or self._not_alive_change)

    def read(self, now_ns: int) -> tuple[int, int, int, int]:
        """(alive_count, not_alive_count, alive_count_change, not_alive_count_change) since the previous read."""
        with self._lock:
            self._expire(now_ns)
            out = (self.alive, self.not_alive, self._alive_change, self._not_alive_change)
            self._alive_change = self._not_alive_change = 0
            return out

    def due_in_ns(self, now_ns: int) -> int | None:
        with self._lock:
            dues = [w.asserted_ns + w.lease_ns - now_ns + 1 for w in self._writers.values()
                    if w.state == _ALIVE and w.manual]
        return max(0, min(dues)) if dues else None


class LostMessages:
    """rmw_zenoh's message-lost status: gaps in each publisher's sequence numbers."""

    def __init__(self) -> None:
        self._last_seq: dict[bytes, int] = {}
        self._lost = 0
        self._read = 0
        self._lock = threading.Lock()

    def arrived(self, gid: bytes, seq: int) -> None:
        with self._lock:
            last = self._last_seq.get(gid)
            if last is not None and seq > last + 1:
                self._lost += seq - last - 1
            self._last_seq[gid] = seq

    def pending(self, now_ns: int) -> bool:
        return self._lost > self._read

    def read(self, now_ns: int) -> tuple[int, int]:
        with self._lock:
            change, self._read = self._lost - self._read, self._lost
            return self._lost, change

    def due_in_ns(self, now_ns: int) -> int | None:
        return None
