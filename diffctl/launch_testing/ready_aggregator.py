"""ReadyAggregator: one ready callback fired when N others have been."""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any


class ReadyAggregator:
    """`ready_fn` of this object, called `num_to_aggregate` times (from any threads), calls the parent's
    `ready_fn` once, on the last call."""

    def __init__(self, ready_fn: Callable[[], Any], num_to_aggregate: int) -> None:
        self._parent_ready_fn = ready_fn
        self._count_to_activate = num_to_aggregate
        self._lock = threading.Lock()

    def ready_fn(self) -> None:
        with self._lock:
            self._count_to_activate -= 1
            last = self._count_to_activate == 0
        if last:  # outside the lock: the parent may call back into whatever holds us
            self._parent_ready_fn()
