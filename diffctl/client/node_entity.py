"""What every entity a node creates (publisher, subscription, service, client) shares, as rclpy's do."""

from __future__ import annotations

from typing import Any, Self

from diffctl.client.destroyable import Handle, handle_of


class NodeEntity:
    """`handle`, the context-manager form and `logger_name`; the entity keeps its node in `_node`."""

    _node: Any

    @property
    def handle(self) -> Handle:
        return handle_of(self)

    def __enter__(self) -> Self:
        return self

    def __exit__(self, *exc: Any) -> None:
        pass

    @property
    def logger_name(self) -> str:
        """The logger name of the node this entity belongs to."""
        return self._node.get_logger().name
