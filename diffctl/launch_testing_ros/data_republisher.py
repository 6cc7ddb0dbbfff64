"""DataRepublisher: listen on a topic, transform each message, publish the result on another."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any


class DataRepublisher:
    """On `node` (an rclpy node the caller spins): messages from `listen_topic` go through `transform_fn`
    and what it returns is published on `publish_topic` (None or a falsy answer drops the message)."""

    def __init__(self, node: Any, listen_topic: str, publish_topic: str, msg_type: Any,
                 transform_fn: Callable[[Any], Any]) -> None:
        self.__node = node
        self.__transform_fn = transform_fn
        self.__num_received = 0
        self.__republished_list: list[Any] = []
        self.__subscriber = node.create_subscription(msg_type, listen_topic, self.__cb, 10)
        self.__publisher = node.create_publisher(msg_type, publish_topic, 10)

    def shutdown(self) -> None:
        """Stop listening and publishing."""
        self.__node.destroy_subscription(self.__subscriber)
        self.__node.destroy_publisher(self.__publisher)

    def get_num_received(self) -> int:
        return self.__num_received

    def get_num_republished(self) -> int:
        """How many messages were republished (fewer than received when the transform dropped some)."""
        return len(self.__republished_list)

    def get_republished(self) -> list[Any]:
        """The received messages that were republished (upstream keeps these, not the transformed ones)."""
        return self.__republished_list

    def __cb(self, msg: Any) -> None:
        self.__num_received += 1
        out = self.__transform_fn(msg)
        if out:
            self.__republished_list.append(msg)
            self.__publisher.publish(out)
