"""The generic relay every topic tool is built on (topic_tools' ToolBaseNode): every 100 ms of wall time it
looks up who publishes the input topic, publishes the output with their type and QoS, and subscribes to the
input (with `lazy`, only while the output has a subscriber); messages pass as raw CDR to `on_message`."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from diffctl.interfaces import get_interface
from diffctl.topic_tools.source_qos import Source, choose

DISCOVERY_PERIOD_S = 0.1


class Relay:
    def __init__(self, node: Any, input_topic: str, output_topic: str, lazy: bool,
                 on_message: Callable[[bytes], None], guard: Callable[[], bool] | None = None) -> None:
        """`guard`: whether the periodic look at the graph should happen now (mux: not while nothing is
        selected)."""
        from diffctl.client.clock import Clock

        self.node, self.log = node, node.get_logger()
        self.input_topic, self.output_topic, self.lazy = input_topic, output_topic, lazy
        self.on_message = on_message
        self.guard = guard
        self.source: Source | None = None
        self.pub: Any = None
        self.sub: Any = None
        self.timer = node.create_timer(DISCOVERY_PERIOD_S, self._on_timer, clock=Clock())
        self._on_timer()

    def _on_timer(self) -> None:
        if self.guard is None or self.guard():
            self.decide()

    def publish(self, data: bytes) -> None:
        if self.pub is not None:
            self.pub.publish(data)

    def _drop_pub(self) -> None:
        if self.pub is not None:
            self.node.destroy_publisher(self.pub)
            self.pub = None

    def _drop_sub(self) -> None:
        if self.sub is not None:
            self.node.destroy_subscription(self.sub)
            self.sub = None

    def decide(self) -> None:
        """Make, keep or drop the publisher and the subscription for what the graph shows now."""
        node = self.node
        source = choose(node.get_publishers_info_by_topic(self.input_topic), self.input_topic)
        if source is None:
            # Nobody to relay: no publisher either (the input's type may change while it is gone).
            self._drop_pub()
            return
        if self.pub is not None and self.pub.topic_name != node.resolve_topic_name(self.output_topic):
            self._drop_pub()
        if self.pub is None or self.source is None or self.source.key() != source.key():
            for text in source.warnings:
                self.log.warning(text)
            try:
                cls = get_interface(source.type_name)
            except (ImportError, ValueError):
                self.log.error(f"cannot relay {self.input_topic}: its type {source.type_name} is unknown here",
                               throttle_duration_sec=10.0)
                return
            self._drop_pub()
            self._drop_sub()
            self.source = source
            self.pub = node.create_publisher(cls, self.output_topic, source.qos)
        if not self.lazy or self.pub.get_subscription_count() > 0:
            if self.sub is not None and self.sub.topic_name != node.resolve_topic_name(self.input_topic):
                self._drop_sub()
            if self.sub is None:
                cls = get_interface(self.source.type_name)
                self.sub = node.create_subscription(cls, self.input_topic, self.on_message, self.source.qos,
                                                    raw=True)
        else:
            self._drop_sub()
