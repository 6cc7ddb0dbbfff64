"""LifecycleNode: a managed node whose transitions become StateTransition events and which makes the
transitions ChangeState events ask of it.

The launch's ROS node (ros_adapters) subscribes `<node>/transition_event` and calls `<node>/change_state`;
a call waits (on a worker thread) for the service, and gives up when the launch shuts down.
"""

from __future__ import annotations

import threading
from typing import Any

import diffctl.launch.logging
from diffctl.launch.action import Action
from diffctl.launch.actions import OpaqueFunction
from diffctl.launch.event_handler import EventHandler
from diffctl.launch.frontend import Entity, Parser, expose_action
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType

from ..events.lifecycle import ChangeState, StateTransition
from ..ros_adapters import get_ros_node
from .node import Node

LOGGER_NAME = "launch_ros.actions.lifecycle_node"


# Jazzy's launch_ros has no tag for it; diffctl's launch files have had `lifecycle_node` (a node's attributes).
@expose_action("lifecycle_node")
class LifecycleNode(Node):
    """A Node with a lifecycle: `name` and `namespace` are required (its services are found by them)."""

    def __init__(self, *, name: SomeSubstitutionsType, namespace: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(name=name, namespace=namespace, **kwargs)
        self.__logger = diffctl.launch.logging.get_logger(LOGGER_NAME)
        self.__current_state = ChangeState.valid_states[0]  # PRIMARY_STATE_UNKNOWN until the node reports
        self.__rclpy_subscription: Any = None
        self.__rclpy_change_state_client: Any = None

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """A `node`'s attributes; without `namespace`, the scope's (as a Node's)."""
        _, kwargs = super().parse(entity, parser)
        kwargs.setdefault("namespace", "")
        return cls, kwargs

    def _on_transition_event(self, context: LaunchContext, msg: Any) -> None:
        """A TransitionEvent (on the adapter's thread) → a StateTransition event on the launch's loop."""
        try:
            event = StateTransition(action=self, msg=msg)
            self.__current_state = ChangeState.valid_states[msg.goal_state.id]
            context.asyncio_loop.call_soon_threadsafe(lambda: context.emit_event_sync(event))
        except Exception as exc:
            self.__logger.error(f"Exception in handling of 'lifecycle.msg.TransitionEvent': {exc}")

    def _call_change_state(self, request: Any, context: LaunchContext) -> None:
        """Call change_state (on a worker thread) once the service is there; give up on shutdown."""
        client = self.__rclpy_change_state_client
        while not client.wait_for_service(timeout_sec=1.0):
            if context.is_shutdown:
                self.__logger.warning(f"Abandoning wait for the '{client.srv_name}' service, due to shutdown.")
                return
        answered = threading.Event()
        future = client.call_async(request)
        future.add_done_callback(lambda _f: answered.set())
        while not answered.wait(1.0):
            if context.is_shutdown:
                self.__logger.warning(
                    f"Abandoning wait for the '{client.srv_name}' service response, due to shutdown."
                )
                future.cancel()
                return
        if future.exception() is not None:
            raise future.exception()
        if not future.result().success:
            self.__logger.error(
                f"Failed to make transition '{ChangeState.valid_transitions[request.transition.id]}' "
                f"for LifecycleNode '{self.node_name}'"
            )

    def _on_change_state_event(self, context: LaunchContext) -> None:
        event = context.locals.event
        if not event.lifecycle_node_matcher(self):
            return
        from lifecycle_msgs.srv import ChangeState as ChangeStateSrv

        request = ChangeStateSrv.Request()
        request.transition.id = event.transition_id
        context.add_completion_future(
            context.asyncio_loop.run_in_executor(None, self._call_change_state, request, context)
        )

    def execute(self, context: LaunchContext) -> list[Action] | None:
        self._perform_substitutions(context)  # node_name is known from here
        if self.UNSPECIFIED_NODE_NAME in self.node_name:
            raise RuntimeError("node_name unexpectedly incomplete for lifecycle node")
        from lifecycle_msgs.msg import TransitionEvent
        from lifecycle_msgs.srv import ChangeState as ChangeStateSrv

        node = get_ros_node(context)
        self.__rclpy_subscription = node.create_subscription(
            TransitionEvent,
            f"{self.node_name}/transition_event",
            lambda msg: self._on_transition_event(context, msg),
            10,
        )
        self.__rclpy_change_state_client = node.create_client(ChangeStateSrv, f"{self.node_name}/change_state")
        context.register_event_handler(
            EventHandler(
                matcher=lambda event: isinstance(event, ChangeState),
                entities=[OpaqueFunction(function=self._on_change_state_event)],
            )
        )
        return super().execute(context)
