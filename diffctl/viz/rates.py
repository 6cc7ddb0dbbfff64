"""Message rates per topic and the real-time factor from /clock, over a sliding window of wall time.

Pure bookkeeping: callers pass the wall time in seconds, so tests need no sleeping.
"""

from __future__ import annotations

from collections import deque

WINDOW_S = 2.0
MAX_SAMPLES = 2000  # a 1 kHz topic over the window; beyond that the rate is still right, just from fewer samples


class RateMeter:
    """`ros2 topic hz` for many topics at once: messages per second over the last WINDOW_S."""

    def __init__(self, window_s: float = WINDOW_S) -> None:
        self.window_s = window_s
        self._stamps: dict[str, deque[float]] = {}

    def record(self, topic: str, wall_s: float) -> None:
        q = self._stamps.get(topic)
        if q is None:
            q = self._stamps[topic] = deque(maxlen=MAX_SAMPLES)
        q.append(wall_s)

    def rate_hz(self, topic: str, wall_s: float) -> float | None:
        """None when nothing arrived within the window (the page shows '—', not a stale number)."""
        q = self._stamps.get(topic)
        if not q:
            return None
        while q and q[0] < wall_s - self.window_s:
            q.popleft()
        if len(q) < 2:
            return None
        span = q[-1] - q[0]
        return (len(q) - 1) / span if span > 0 else None

    def topics(self) -> list[str]:
        return sorted(self._stamps)


class RtfMeter:
    """Real-time factor as Δsim / Δwall over the window; a jump back in sim time restarts it."""

    def __init__(self, window_s: float = WINDOW_S) -> None:
        self.window_s = window_s
        self._samples: deque[tuple[float, float]] = deque(maxlen=MAX_SAMPLES)

    def record(self, sim_s: float, wall_s: float) -> bool:
        """Add a sample; True when sim time went backwards (the caller resets what depends on it)."""
        jumped = bool(self._samples) and sim_s < self._samples[-1][1]
        if jumped:
            self._samples.clear()
        self._samples.append((wall_s, sim_s))
        return jumped

    def rtf(self, wall_s: float) -> float | None:
        while len(self._samples) > 2 and self._samples[0][0] < wall_s - self.window_s:
            self._samples.popleft()
        if len(self._samples) < 2 or self._samples[-1][0] < wall_s - self.window_s:
            return None
        (w0, s0), (w1, s1) = self._samples[0], self._samples[-1]
        return (s1 - s0) / (w1 - w0) if w1 > w0 else None

    @property
    def sim_s(self) -> float | None:
        return self._samples[-1][1] if self._samples else None
