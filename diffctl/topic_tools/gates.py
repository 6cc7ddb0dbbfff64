"""What each topic tool lets through, apart from any I/O: a message rate, a byte rate over a window, or X
dropped out of every Y. Times are nanoseconds of whichever clock the node measures with."""

from __future__ import annotations

from collections import deque


class MessageThrottle:
    """At most one message per period: a message passes when a full period has gone since the last one."""

    def __init__(self, msgs_per_sec: float, start_ns: int) -> None:
        self.period_ns = int(1e9 / msgs_per_sec)
        self.last_ns = start_ns
        self.jumped_back = False  # set by the admit that found the clock behind the last message

    def admit(self, now_ns: int) -> bool:
        """Whether a message arriving at `now_ns` goes out; a clock that went back restarts the period."""
        self.jumped_back = self.last_ns > now_ns
        if self.jumped_back:
            self.last_ns = now_ns
        if now_ns - self.last_ns >= self.period_ns:
            self.last_ns = now_ns
            return True
        return False


class ByteThrottle:
    """A message passes while the bytes sent in the last `window_s` are under `bytes_per_sec`."""

    def __init__(self, bytes_per_sec: int, window_s: float) -> None:
        self.bytes_per_sec = bytes_per_sec
        self.window_s = window_s
        self.sent: deque[tuple[float, int]] = deque()

    def admit(self, now_ns: int, size: int) -> bool:
        now_s = now_ns * 1e-9
        while self.sent and self.sent[0][0] < now_s - self.window_s:
            self.sent.popleft()
        if sum(n for _, n in self.sent) < self.bytes_per_sec:
            self.sent.append((now_s, size))
            return True
        return False


class Drop:
    """Drops the first X of every Y messages."""

    def __init__(self, x: int, y: int) -> None:
        self.x, self.y = x, y
        self.count = 0

    def admit(self) -> bool:
        passes = self.count >= self.x
        self.count += 1
        if self.count >= self.y:
            self.count = 0
        return passes
