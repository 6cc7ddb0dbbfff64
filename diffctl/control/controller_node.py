"""The node handle a controller gets: a bus Node named /<controller>, its parameters, and the manager's clock.

Parameters are the bus Node's (declared with descriptors, served by the six parameter services, changes
announced on /parameter_events): a controller declares its table in on_init and may register a set-callback
to refuse a change or take it on its next update.

The controller's time is the manager's: wall time, or sim time (the newest of the current cycle's time
and /clock), so a command stamped by a teleop node on the same clock is compared with the same clock
the controller's update() runs on.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from diffctl.bus import Node


class BusControllerNode:
    def __init__(
        self,
        name: str,
        namespace: str,
        params: dict[str, Any],
        now_ns: Callable[[], int],
        remaps: dict[str, str] | None = None,
    ) -> None:
        # The node's own /clock subscription is not needed: time comes from the manager.
        self._node = Node(name, namespace, params=params, use_sim_time=False, remaps=remaps)
        self.name = name
        self.params = self._node.params
        self.log = self._node.log
        self._now_ns = now_ns

    @property
    def fqn(self) -> str:
        return self._node.fqn

    def create_publisher(self, topic: str, type_name: str, latched: bool = False, depth: int = 10) -> Any:
        """A publisher for the control loop: serialized there, put on the bus by the publishing thread
        (realtime_tools' RealtimePublisher, which ros2_controllers' controllers publish through)."""
        from diffctl.control.realtime_publisher import RealtimePublisher

        return RealtimePublisher(self._node.create_publisher(topic, type_name, latched=latched, depth=depth))

    def create_subscription(
        self, topic: str, type_name: str, callback: Callable[[Any], None], latched: bool = False, depth: int = 10
    ) -> Any:
        return self._node.create_subscription(topic, type_name, callback, latched=latched, depth=depth)

    # --- parameters ----------------------------------------------------------------------------------------
    @property
    def parameters(self) -> Any:
        return self._node.parameters

    def declare_parameter(self, name: str, default: Any, descriptor: Any = None) -> Any:
        return self._node.declare_parameter(name, default, descriptor)

    def get_parameter(self, name: str) -> Any:
        return self._node.get_parameter(name)

    def set_parameters(self, values: dict[str, Any]) -> list[str | None]:
        return self._node.set_parameters(values)

    def add_on_set_parameters_callback(self, cb: Callable[[dict[str, Any]], str | None]) -> None:
        self._node.add_on_set_parameters_callback(cb)

    def now_ns(self) -> int:
        return self._now_ns()

    def now(self) -> Any:
        from diffctl.interfaces.types import time_msg

        return time_msg(self._now_ns())

    def resolve(self, name: str) -> str:
        return self._node.resolve(name)

    def close(self) -> None:
        self._node.close()

    def __getattr__(self, item: str) -> Any:
        # Anything else a controller may want of a node (graph, create_timer, session) comes from the bus Node.
        if item.startswith("_"):
            raise AttributeError(item)
        return getattr(self._node, item)
