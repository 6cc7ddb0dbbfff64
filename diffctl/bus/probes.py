"""Readiness probes the CLI injects into the launch engine (which knows processes, not topics)."""

from __future__ import annotations

from diffctl.bus.graph import Graph
from diffctl.bus.session import open_session


class BusProbes:
    def __init__(self) -> None:
        self._graph: Graph | None = None

    @property
    def graph(self) -> Graph:
        if self._graph is None:
            self._graph = Graph(open_session())
        return self._graph

    def topic_has_publisher(self, name: str) -> bool:
        return bool(self.graph.publishers("/" + name.lstrip("/")))

    def service_available(self, name: str) -> bool:
        return bool(self.graph.servers("/" + name.lstrip("/")))

    def close(self) -> None:
        if self._graph is not None:
            self._graph.close()
            self._graph = None
