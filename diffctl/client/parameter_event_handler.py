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
    def __init__(self, node: Any, qos_profile: Any = qos_profile_parameter_events, callback_group: Any = None,
                 event_callbacks: Any = None, qos_overriding_options: Any = None, raw: bool = False) -> None:
        self.node = node
        self.qos_profile = qos_profile
        self._mutex = threading.Lock()
        self._parameter_callbacks: dict[tuple[str, str], list[ParameterCallbackHandle]] = {}
        self._event_callbacks: list[ParameterEventCallbackHandle] = []
        self.parameter_event_subscription = node.create_subscription(
            cls("rcl_interfaces/msg/ParameterEvent"), "/parameter_events", self._on_event, qos_profile,
            callback_group=callback_group, event_callbacks=event_callbacks,
            qos_overriding_options=qos_overriding_options, raw=raw)

    def _on_event(self, event: Any) -> None:
        with self._mutex:
            for (param_name, node_name), handles in self._parameter_callbacks.items():
                parameter = self.get_parameter_from_event(event, parameter_name=param_name, node_name=node_name)
                if parameter is not None:
                    for h in handles:
                        with h.mutex:
                            h.callback(parameter)
            for h in self._event_callbacks:
                with h.mutex:
                    h.callback(event)

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
        handle = ParameterCallbackHandle(parameter_name, self._resolve_path(node_name), callback)
        with self._mutex:
            self._parameter_callbacks.setdefault((parameter_name, handle.node_name), []).insert(0, handle)
        return handle

    def remove_parameter_callback(self, handle: ParameterCallbackHandle) -> None:
        key = (handle.parameter_name, handle.node_name)
        with self._mutex:
            handles = self._parameter_callbacks.get(key)
            if not handles or handle not in handles:
                raise RuntimeError("Callback doesn't exist")
            handles.remove(handle)
            if not handles:
                del self._parameter_callbacks[key]

    def add_parameter_event_callback(self, callback: Callable[[Any], None]) -> ParameterEventCallbackHandle:
        handle = ParameterEventCallbackHandle(callback)
        with self._mutex:
            self._event_callbacks.insert(0, handle)
        return handle

    def remove_parameter_event_callback(self, handle: ParameterEventCallbackHandle) -> None:
        with self._mutex:
            if handle not in self._event_callbacks:
                raise RuntimeError("Callback doesn't exist")
            self._event_callbacks.remove(handle)

    def _resolve_path(self, node_path: str | None = None) -> str:
        if not node_path:
            return self.node.get_fully_qualified_name()
        if node_path.startswith("/"):
            return node_path
        resolved = "/".join([self.node.get_namespace().lstrip("/"), node_path])
        return resolved if resolved.startswith("/") else f"/{resolved}"
