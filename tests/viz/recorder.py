"""Messages of one topic seen by a subscriber in the test process, for the visualizer's tests."""

from __future__ import annotations

import threading

from tests.probe import Probe


class Recorder:
    def __init__(self, node: Probe, topic: str, type_name: str) -> None:
        self.msgs: list = []
        self._lock = threading.Lock()
        node.create_subscription(topic, type_name, self._on)

    def _on(self, msg) -> None:
        with self._lock:
            self.msgs.append(msg)

    def snapshot(self) -> list:
        with self._lock:
            return list(self.msgs)
