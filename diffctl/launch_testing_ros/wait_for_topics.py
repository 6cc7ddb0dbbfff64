"""WaitForTopics: wait until each of some topics has carried a message (rclpy API: diffctl.client, or the
real rclpy where a sourced ROS 2 provides it).

It has a context, node and executor of its own, spun on a thread, so a test body's own rclpy use is not
touched: `with WaitForTopics([('chatter', String)], timeout=5.0) as w: …` or wait() / shutdown().
"""

from __future__ import annotations

import random
import string
import threading
from collections import deque
from typing import Any


class WaitForTopics:
    def __init__(self, topic_tuples: list[tuple[str, Any]], timeout: float = 5.0,
                 messages_received_buffer_length: int = 10) -> None:
        import rclpy
        from rclpy.executors import SingleThreadedExecutor

        self.topic_tuples = topic_tuples
        self.timeout = timeout
        self.messages_received_buffer_length = messages_received_buffer_length
        self.__context = rclpy.Context()
        rclpy.init(context=self.__context)
        self.__executor = SingleThreadedExecutor(context=self.__context)
        name = "_test_node_" + "".join(random.choices(string.ascii_uppercase + string.digits, k=10))
        self.__node = rclpy.create_node(name, context=self.__context)
        self.__executor.add_node(self.__node)
        self.__lock = threading.Lock()
        self.__all_received = threading.Event()
        self.__subscribed: list[tuple[str, Any]] = []
        self.__expected: set[str] = set()
        self.__received: set[str] = set()
        self.__buffers: dict[str, deque[Any]] = {}
        self.__spin_thread = threading.Thread(target=self.__spin, name="wait_for_topics")
        self.__spin_thread.start()

    def __spin(self) -> None:
        from rclpy.executors import ExternalShutdownException

        try:
            self.__executor.spin()
        except ExternalShutdownException:
            pass

    def __callback(self, topic: str) -> Any:
        def on_message(msg: Any) -> None:
            with self.__lock:
                self.__buffers[topic].append(msg)
                self.__received.add(topic)
                if self.__received == self.__expected:
                    self.__all_received.set()

        return on_message

    def wait(self) -> bool:
        """Subscribe (once per topic) and wait until every topic carried a message since this call; False at
        the timeout."""
        with self.__lock:
            self.__all_received.clear()
            self.__received = set()
            for buffer in self.__buffers.values():
                buffer.clear()
            for topic, msg_type in self.topic_tuples:
                if (topic, msg_type) in self.__subscribed:
                    continue
                self.__subscribed.append((topic, msg_type))
                self.__expected.add(topic)
                self.__buffers[topic] = deque(maxlen=self.messages_received_buffer_length)
                self.__node.create_subscription(msg_type, topic, self.__callback(topic), 10)
        return self.__all_received.wait(self.timeout)

    def shutdown(self) -> None:
        self.__context.try_shutdown()
        self.__spin_thread.join()
        self.__node.destroy_node()

    def topics_received(self) -> set[str]:
        """The topics that carried a message."""
        with self.__lock:
            return set(self.__received)

    def topics_not_received(self) -> set[str]:
        """The topics still silent."""
        with self.__lock:
            return self.__expected - self.__received

    def received_messages(self, topic_name: str) -> list[Any]:
        """The last messages of a topic (up to messages_received_buffer_length)."""
        with self.__lock:
            if topic_name not in self.__buffers:
                raise KeyError("No messages received for topic: " + topic_name)
            return list(self.__buffers[topic_name])

    def __enter__(self) -> WaitForTopics:
        if not self.wait():
            self.shutdown()  # no spinning thread left behind: __exit__ is not called after this
            raise RuntimeError("Did not receive messages on these topics: ", self.topics_not_received())
        return self

    def __exit__(self, exc_type: Any, exc_value: Any, trace: Any) -> None:
        self.shutdown()
