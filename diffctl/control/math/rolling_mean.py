"""Mean of the last N samples (rcppmath::RollingMeanAccumulator), used for the odometry twist."""

from __future__ import annotations


class RollingMean:
    """Mean over a ring buffer of `window` samples; before it fills, the mean of the samples seen so far."""

    __slots__ = ("_buffer", "_count", "_next", "window")

    def __init__(self, window: int) -> None:
        if window < 1:
            raise ValueError(f"rolling window must be ≥ 1, got {window!r}")
        self.window = window
        self._buffer = [0.0] * window
        self._next = 0
        self._count = 0

    def accumulate(self, value: float) -> None:
        self._buffer[self._next] = value
        self._next = (self._next + 1) % self.window
        if self._count < self.window:
            self._count += 1

    @property
    def mean(self) -> float:
        if self._count == 0:
            return 0.0
        # Summing the (small) buffer each time, instead of keeping a running sum, avoids drift on long runs.
        if self._count == self.window:
            return sum(self._buffer) / self.window
        return sum(self._buffer[: self._count]) / self._count  # not yet wrapped: samples are [0, count)

    def reset(self) -> None:
        self._buffer = [0.0] * self.window
        self._next = 0
        self._count = 0
