"""launch_testing_ros.WaitForTopics: wait until every listed topic has carried a message.

Written on the rclpy API (diffctl's rclpy-compatible client, or the real rclpy where it is installed): a context
and node of its own, spun on a thread, so a test body's own rclpy use is untouched.
"""

from __future__ import annotations

import random
import string
import threading
from collections import deque
from typing import Any


class WaitForTopics:
    """`WaitForTopics([('chatter', String)], timeout=5.0).wait()` → True once each topic had a message.

    As a context manager it raises RuntimeError on entry when a topic stayed silent, and shuts down on exit.
    """

    def __init__(self, topic_tuples: list[tuple[str, Any]], timeout: float = 5.0,
                 messages_received_buffer_length: int = 10) -> None:
        import rclpy
        from rclpy.executors import SingleThreadedExecutor

        self.topic_tuples = list(topic_tuples)
        self.timeout = timeout
        self.messages_received_buffer_length = messages_received_buffer_length
        self._context = rclpy.Context()
        rclpy.init(context=self._context)
        suffix = "".join(random.choices(string.ascii_uppercase + string.digits, k=10))
        self._node = rclpy.create_node(f"_test_node_{suffix}", context=self._context)
        self._executor = SingleThreadedExecutor(context=self._context)
        self._executor.add_node(self._node)
        self._lock = threading.Condition()
        self._subscriptions: dict[str, Any] = {}
        self._received: dict[str, deque[Any]] = {}
        self._expected: set[str] = set()
        self._spinning = True
        self._thread = threading.Thread(target=self._spin, name="wait_for_topics", daemon=True)
        self._thread.start()

    def _spin(self) -> None:
        while self._spinning:
            try:
                self._executor.spin_once(timeout_sec=0.1)
            except Exception:
                if not self._spinning:
                    return
                raise

    def _callback(self, topic: str) -> Any:
        def on_message(msg: Any) -> None:
            with self._lock:
                self._received[topic].append(msg)
                self._lock.notify_all()

        return on_message

    def wait(self) -> bool:
        """Block until every topic has carried a message since this call (False at the timeout)."""
        with self._lock:
            self._expected = {name for name, _ in self.topic_tuples}
            for name in self._expected:
                self._received[name] = deque(maxlen=self.messages_received_buffer_length)
        for name, msg_type in self.topic_tuples:
            if name not in self._subscriptions:
                self._subscriptions[name] = self._node.create_subscription(msg_type, name, self._callback(name), 10)
        import time

        deadline = time.monotonic() + self.timeout
        with self._lock:
            while self.topics_not_received():
                left = deadline - time.monotonic()
                if left <= 0:
                    return False
                self._lock.wait(left)
        return True

    def topics_received(self) -> set[str]:
        with self._lock:
            return {name for name in self._expected if self._received.get(name)}

    def topics_not_received(self) -> set[str]:
        with self._lock:
            return {name for name in self._expected if not self._received.get(name)}

    def received_messages(self, topic_name: str) -> list[Any]:
        if topic_name not in self._received:
            raise KeyError(f"No messages received for topic {topic_name}")
        with self._lock:
            return list(self._received[topic_name])

    def shutdown(self) -> None:
        import rclpy

        self._spinning = False
        self._thread.join(2.0)
        self._node.destroy_node()
        rclpy.shutdown(context=self._context)

    def __enter__(self) -> WaitForTopics:
        if not self.wait():
            self.shutdown()
            raise RuntimeError("Did not receive messages on these topics: " + str(self.topics_not_received()))
        return self

    def __exit__(self, *exc: Any) -> None:
        self.shutdown()
