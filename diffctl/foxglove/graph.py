"""The connectionGraph capability of `foxglove-bridge`: which nodes publish and subscribe each topic and
provide each service, sent to clients that watch the graph (the app's Topic Graph panel), as
foxglove_bridge's updateConnectionGraph builds it (node ids are fully qualified node names).

The SDK deadlocks when the graph is published from inside its subscribe callback, so a new watcher only
wakes the graph thread, which publishes on it (and again on every graph change while anyone watches).
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

import foxglove


def connection_graph(graph: Any) -> foxglove.ConnectionGraph:
    out = foxglove.ConnectionGraph()
    for topic in graph.topics():
        out.set_published_topic(topic, sorted({e.node_fqn for e in graph.publishers(topic)}))
        out.set_subscribed_topic(topic, sorted({e.node_fqn for e in graph.subscribers(topic)}))
    for service in graph.services():
        out.set_advertised_service(service, sorted({e.node_fqn for e in graph.servers(service)}))
    return out


class GraphBridge:
    def __init__(self, node: Any, wake: Callable[[], None]) -> None:
        self.node = node
        self.wake = wake
        self.server: Any = None
        self._watchers = 0
        self._lock = threading.Lock()

    def on_subscribe(self) -> None:
        with self._lock:
            self._watchers += 1
        self.wake()

    def on_unsubscribe(self) -> None:
        with self._lock:
            self._watchers = max(0, self._watchers - 1)

    def sync(self) -> None:
        """On the graph thread: the current graph to the watchers (the SDK sends each only what changed)."""
        with self._lock:
            watched = self._watchers > 0
        if watched and self.server is not None:
            self.server.publish_connection_graph(connection_graph(self.node.graph))
