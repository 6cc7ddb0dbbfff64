"""launch_testing_ros' helpers for test bodies: DataRepublisher (listen, transform, publish again) and
MessagePump (spin a node on a thread), on the rclpy API."""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any


class DataRepublisher:
    """Messages from `listen_topic`, passed through `transform_fn` (None drops one), published on
    `publish_topic`; counts what it received and what it republished."""

    def __init__(self, node: Any, listen_topic: str, publish_topic: str, msg_type: Any,
                 transform_fn: Callable[[Any], Any]) -> None:
        self._node = node
        self._transform = transform_fn
        self._received = 0
        self._republished: list[Any] = []
        self._subscription = node.create_subscription(msg_type, listen_topic, self._on_message, 10)
        self._publisher = node.create_publisher(msg_type, publish_topic, 10)

    def _on_message(self, msg: Any) -> None:
        self._received += 1
        out = self._transform(msg)
        if out:
            self._republished.append(msg)
            self._publisher.publish(out)

    def get_num_received(self) -> int:
        return self._received

    def get_num_republished(self) -> int:
        return len(self._republished)

    def get_republished(self) -> list[Any]:
        return list(self._republished)

    def shutdown(self) -> None:
        self._node.destroy_subscription(self._subscription)
        self._node.destroy_publisher(self._publisher)


class MessagePump:
    """Spins `node` on a thread of its own between start() and stop()."""

    def __init__(self, node: Any, context: Any = None) -> None:
        self._node = node
        self._context = context
        self._running = False
        self._thread = threading.Thread(target=self._spin, name="msg_pump_thread")

    def start(self) -> None:
        self._running = True
        self._thread.start()

    def stop(self) -> None:
        self._running = False
        self._thread.join(timeout=5.0)
        if self._thread.is_alive():
            raise Exception("Timed out waiting for message pump to stop")

    def _spin(self) -> None:
        from rclpy.executors import SingleThreadedExecutor

        executor = SingleThreadedExecutor(context=self._context)
        executor.add_node(self._node)
        try:
            while self._running:
                executor.spin_once(timeout_sec=0.1)
        finally:
            executor.remove_node(self._node)
