"""The bus side of launch_ros's LifecycleNode for `diffctl launch`: transition events and change_state calls.

As launch_ros's ROS adapter: one node of launch's own (`launch_ros_<pid>`, own context, its executor on a
thread) subscribes `<node>/transition_event` and calls `<node>/change_state`. Its callbacks run on that thread
and hand their results to the launch's thread through `post`. Built only when a launch first uses a
LifecycleNode (the engine imports no bus: the CLI layer gives the supervisor this factory).
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from typing import Any


class LifecycleBridge:
    def __init__(self, post: Callable[[Callable[[], None]], None]) -> None:
        import rclpy
        from rclpy.context import Context
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.signals import SignalHandlerOptions

        self.post = post
        self.context = Context()
        rclpy.init(args=[], context=self.context, signal_handler_options=SignalHandlerOptions.NO)
        self.node = rclpy.create_node(f"launch_ros_{os.getpid()}", context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self.thread = threading.Thread(target=self._spin, name="launch-lifecycle", daemon=True)
        self.thread.start()
        self.clients: dict[str, Any] = {}
        self.subscriptions: list[Any] = []

    def _spin(self) -> None:
        try:
            self.executor.spin()
        except Exception:  # shut down under it
            return

    def watch_transitions(self, node_fqn: str, on_transition: Callable[[str, str, str, Any], None]) -> None:
        from lifecycle_msgs.msg import TransitionEvent

        def callback(msg: Any) -> None:
            on_transition(msg.transition.label, msg.start_state.label, msg.goal_state.label, msg)

        self.subscriptions.append(
            self.node.create_subscription(TransitionEvent, f"{node_fqn}/transition_event", callback, 10)
        )

    def change_state(self, node_fqn: str, transition_id: int, done: Callable[[bool, str], None]) -> None:
        """Wait for the node's service (as launch_ros: until it comes or the launch ends), then call it."""
        from lifecycle_msgs.srv import ChangeState

        client = self.clients.get(node_fqn)
        if client is None:
            client = self.clients[node_fqn] = self.node.create_client(ChangeState, f"{node_fqn}/change_state")

        def call() -> None:
            while self.context.ok() and not client.wait_for_service(timeout_sec=1.0):
                pass
            if not self.context.ok():
                return
            request = ChangeState.Request()
            request.transition.id = transition_id
            future = client.call_async(request)

            def answered(f: Any) -> None:
                error = f.exception()
                ok = error is None and bool(f.result().success)
                self.post(lambda: done(ok, str(error) if error else "the node refused the transition"))

            future.add_done_callback(answered)

        threading.Thread(target=call, name="launch-change-state", daemon=True).start()

    def close(self) -> None:
        try:
            self.executor.shutdown(timeout_sec=1.0)
            self.node.destroy_node()
            self.context.try_shutdown()
        except Exception:
            pass


def make(post: Callable[[Callable[[], None]], None]) -> LifecycleBridge:
    return LifecycleBridge(post)
