"""Which velocity command twist_mux lets through, apart from any I/O.

Each input and each lock has a name, a topic, a timeout (0: never expires) and a priority (0-255). An input
is masked when its last message is older than its timeout or a lock of higher priority is on; a lock is
on while its last Bool was true or it has expired (a lock whose publisher died stops what it guards). A
message goes out when its input is the highest-priority one left unmasked (ties: the first by name;
priority 0 never wins, as upstream's strict comparison from 0 has it).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any


@dataclass
class Handle:
    name: str
    topic: str
    timeout_s: float
    priority: int
    stamp_ns: int = 0  # when the last message came, on the node's clock (0: never)
    message: Any = None

    def __post_init__(self) -> None:
        self.priority = max(0, min(255, self.priority))

    def expired(self, now_ns: int) -> bool:
        return self.timeout_s > 0.0 and (now_ns - self.stamp_ns) * 1e-9 > self.timeout_s

    def masked(self, lock_priority: int, now_ns: int) -> bool:
        return self.expired(now_ns) or self.priority < lock_priority

    def locked(self, now_ns: int) -> bool:
        return self.expired(now_ns) or bool(self.message is not None and self.message.data)


def lock_priority(locks: list[Handle], now_ns: int) -> int:
    """The highest priority among the locks that are on (0: none)."""
    return max((lock.priority for lock in locks if lock.locked(now_ns)), default=0)


def winner(velocities: list[Handle], locks: list[Handle], now_ns: int) -> str | None:
    """The name of the input whose messages pass now, or None."""
    floor = lock_priority(locks, now_ns)
    best, name = 0, None
    for v in velocities:
        if not v.masked(floor, now_ns) and best < v.priority:
            best, name = v.priority, v.name
    return name
