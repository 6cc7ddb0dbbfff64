"""rclpy.parameter_event_handler: callbacks on /parameter_events, for every event or one node's parameter.

Callbacks run from the handler's subscription (so in the executor), newest first; a parameter callback gets
the rcl_interfaces/msg/Parameter of the event, as rclpy's does.
"""

from __future__ import annotations

import itertools
import threading
from collections.abc import Callable, Iterator
from typing import Any

from diffctl.client.interfaces import cls
from diffctl.client.qos import qos_profile_parameter_events


class ParameterCallbackHandle:
    def __init__(self, parameter_name: str, node_name: str, callback: Callable[[Any], None]) -> None:
        self.parameter_name = parameter_name
        self.node_name = node_name
        self.callback = callback
        self.mutex = threading.Lock()


class ParameterEventCallbackHandle:
    def __init__(self, callback: Callable[[Any], None]) -> None:
        self.callback = callback
        self.mutex = threading.Lock()


class ParameterEventHandler:
    class Callbacks:
        """The handler's registry (rclpy's `handler._callbacks`): parameter callbacks by (parameter, node) and
        event callbacks, each newest first; `event_callback` serves one ParameterEvent."""

        def __init__(self) -> None:
            self.parameter_callbacks: dict[tuple[str, str], list[ParameterCallbackHandle]] = {}
            self.event_callbacks: list[ParameterEventCallbackHandle] = []
            self.mutex = threading.Lock()

        def event_callback(self, event: Any) -> None:
            with self.mutex:
                for (param_name, node_name), handles in self.parameter_callbacks.items():
                    parameter = ParameterEventHandler.get_parameter_from_event(
                        event, parameter_name=param_name, node_name=node_name)
                    if parameter is not None:
                        for h in handles:
                            with h.mutex:
                                h.callback(parameter)
                for h in self.event_callbacks:
                    with h.mutex:
                        h.callback(event)

        def add_parameter_callback(self, parameter_name: str, node_name: str,
                                   callback: Callable[[Any], None]) -> ParameterCallbackHandle:
            handle = ParameterCallbackHandle(parameter_name, node_name, callback)
            with self.mutex:
                self.parameter_callbacks.setdefault((parameter_name, node_name), []).insert(0, handle)
            return handle

        def remove_parameter_callback(self, handle: ParameterCallbackHandle) -> None:
            key = (handle.parameter_name, handle.node_name)
            with self.mutex:
                handles = self.parameter_callbacks.get(key)
                if not handles or handle not in handles:
                    raise RuntimeError("Callback doesn't exist")
                handles.remove(handle)
                if not handles:
                    del self.parameter_callbacks[key]

        def add_parameter_event_callback(self, callback: Callable[[Any], None]) -> ParameterEventCallbackHandle:
            handle = ParameterEventCallbackHandle(callback)
            with self.mutex:
                self.event_callbacks.insert(0, handle)
            return handle

        def remove_parameter_event_callback(self, handle: ParameterEventCallbackHandle) -> None:
            with self.mutex:
                if handle not in self.event_callbacks:
                    raise RuntimeError("Callback doesn't exist")
                self.event_callbacks.remove(handle)

    def __init__(self, node: Any, qos_profile: Any = qos_profile_parameter_events, callback_group: Any = None,
                 event_callbacks: Any = None, qos_overriding_options: Any = None, raw: bool = False) -> None:
        self.node = node
        self.qos_profile = qos_profile
        self._callbacks = ParameterEventHandler.Callbacks()
        self.parameter_event_subscription = node.create_subscription(
            cls("rcl_interfaces/msg/ParameterEvent"), "/parameter_events", self._callbacks.event_callback,
            qos_profile, callback_group=callback_group, event_callbacks=event_callbacks,
            qos_overriding_options=qos_overriding_options, raw=raw)

    def destroy(self) -> None:
        self.node.destroy_subscription(self.parameter_event_subscription)

    @staticmethod
    def get_parameter_from_event(event: Any, parameter_name: str, node_name: str) -> Any:
        if event.node == node_name:
            for p in itertools.chain(event.new_parameters, event.changed_parameters):
                if p.name == parameter_name:
                    return p
        return None

    @staticmethod
    def get_parameters_from_event(event: Any) -> Iterator[Any]:
        yield from itertools.chain(event.new_parameters, event.changed_parameters)

    def add_parameter_callback(self, parameter_name: str, node_name: str,
                               callback: Callable[[Any], None]) -> ParameterCallbackHandle:
        return self._callbacks.add_parameter_callback(parameter_name, self._resolve_path(node_name), callback)

    def remove_parameter_callback(self, handle: ParameterCallbackHandle) -> None:
        self._callbacks.remove_parameter_callback(handle)

    def add_parameter_event_callback(self, callback: Callable[[Any], None]) -> ParameterEventCallbackHandle:
        return self._callbacks.add_parameter_event_callback(callback)

    def remove_parameter_event_callback(self, handle: ParameterEventCallbackHandle) -> None:
        self._callbacks.remove_parameter_event_callback(handle)

    def _resolve_path(self, node_path: str | None = None) -> str:
        if not node_path:
            return self.node.get_fully_qualified_name()
        if node_path.startswith("/"):
            return node_path
        resolved = "/".join([self.node.get_namespace().lstrip("/"), node_path])
        return resolved if resolved.startswith("/") else f"/{resolved}"
