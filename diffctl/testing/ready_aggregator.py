"""launch_testing's ReadyAggregator: call `ready_fn` once, when `ready_check()` was called N times."""

from __future__ import annotations

import threading
from collections.abc import Callable


class ReadyAggregator:
    def __init__(self, ready_fn: Callable[[], object], num_to_aggregate: int) -> None:
        self._ready_fn = ready_fn
        self._count_to_activate = num_to_aggregate
        self._lock = threading.Lock()

    def ready_check(self, *args: object, **kwargs: object) -> None:
        with self._lock:
            self._count_to_activate -= 1
            fire = self._count_to_activate == 0
        if fire:
            self._ready_fn()
