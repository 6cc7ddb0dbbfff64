"""The publishers and subscriptions a controller created, so cleanup can destroy exactly those."""

from __future__ import annotations

from typing import Any, TypeVar

T = TypeVar("T")


class OwnedEndpoints:
    def __init__(self) -> None:
        self._items: list[Any] = []

    def keep(self, endpoint: T) -> T:
        self._items.append(endpoint)
        return endpoint

    def close_all(self) -> None:
        for endpoint in self._items:
            endpoint.destroy()  # rclpy's Publisher/Subscription.destroy(): off the node and the wire
        self._items.clear()
