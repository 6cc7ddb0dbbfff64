"""rclpy.parameter_client.AsyncParameterClient: another node's parameter services, each call a Future."""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from typing import Any

from diffctl.client.interfaces import cls
from diffctl.client.parameter import Parameter, parameter_dict_from_yaml_file
from diffctl.client.qos import qos_profile_parameter_events, qos_profile_services_default
from diffctl.client.task import Future

_SERVICES = {
    "get": ("GetParameters", "get_parameters"), "list": ("ListParameters", "list_parameters"),
    "set": ("SetParameters", "set_parameters"), "types": ("GetParameterTypes", "get_parameter_types"),
    "describe": ("DescribeParameters", "describe_parameters"),
    "atomic": ("SetParametersAtomically", "set_parameters_atomically"),
}


class AsyncParameterClient:
    def __init__(self, node: Any, remote_node_name: str, qos_profile: Any = qos_profile_services_default,
                 callback_group: Any = None) -> None:
        self.remote_node_name = remote_node_name
        self.node = node
        self._clients = {
            key: node.create_client(cls(f"rcl_interfaces/srv/{srv}"), f"{remote_node_name}/{name}",
                                    qos_profile=qos_profile, callback_group=callback_group)
            for key, (srv, name) in _SERVICES.items()
        }

    def services_are_ready(self) -> bool:
        return all(c.service_is_ready() for c in self._clients.values())

    def wait_for_services(self, timeout_sec: float | None = None) -> bool:
        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        graph = self.node.bus_node.graph
        while not self.services_are_ready():
            left = None if deadline is None else deadline - time.monotonic()
            if left is not None and left <= 0:
                break
            graph.wait_for(self.services_are_ready, 0.25 if left is None else min(left, 0.25))
        return self.services_are_ready()

    def _call(self, key: str, callback: Callable[[Future], None] | None, **fields: Any) -> Future:
        client = self._clients[key]
        request = client.srv_type.Request()
        for name, value in fields.items():
            setattr(request, name, value)
        future = client.call_async(request)
        if callback:
            future.add_done_callback(callback)
        return future

    @staticmethod
    def _msgs(parameters: Sequence[Any]) -> list[Any]:
        return [p.to_parameter_msg() if isinstance(p, Parameter) else p for p in parameters]

    def list_parameters(self, prefixes: list[str] | None = None, depth: int | None = None,
                        callback: Callable[[Future], None] | None = None) -> Future:
        fields: dict[str, Any] = {}
        if prefixes:
            fields["prefixes"] = prefixes
        if depth:
            fields["depth"] = depth
        return self._call("list", callback, **fields)

    def get_parameters(self, names: list[str], callback: Callable[[Future], None] | None = None) -> Future:
        return self._call("get", callback, names=names)

    def set_parameters(self, parameters: Sequence[Any], callback: Callable[[Future], None] | None = None) -> Future:
        return self._call("set", callback, parameters=self._msgs(parameters))

    def describe_parameters(self, names: list[str], callback: Callable[[Future], None] | None = None) -> Future:
        return self._call("describe", callback, names=names)

    def get_parameter_types(self, names: list[str], callback: Callable[[Future], None] | None = None) -> Future:
        return self._call("types", callback, names=names)

    def set_parameters_atomically(self, parameters: Sequence[Any],
                                  callback: Callable[[Future], None] | None = None) -> Future:
        return self._call("atomic", callback, parameters=self._msgs(parameters))

    def delete_parameters(self, names: list[str], callback: Callable[[Future], None] | None = None) -> Future:
        return self._call("set", callback, parameters=[Parameter(name=n).to_parameter_msg() for n in names])

    def load_parameter_file(self, parameter_file: str, use_wildcard: bool = False,
                            callback: Callable[[Future], None] | None = None) -> Future:
        params = parameter_dict_from_yaml_file(parameter_file, use_wildcard)
        return self.set_parameters(list(params.values()), callback=callback)

    def load_parameter_file_atomically(self, parameter_file: str, use_wildcard: bool = False,
                                       callback: Callable[[Future], None] | None = None) -> Future:
        params = parameter_dict_from_yaml_file(parameter_file, use_wildcard)
        return self.set_parameters_atomically(list(params.values()), callback=callback)

    def on_parameter_event(self, callback: Callable[[Any], None], qos_profile: Any = qos_profile_parameter_events,
                           *, callback_group: Any = None, event_callbacks: Any = None,
                           qos_overriding_options: Any = None, raw: bool = False) -> Any:
        return self.node.create_subscription(
            cls("rcl_interfaces/msg/ParameterEvent"), "/parameter_events", callback, qos_profile,
            callback_group=callback_group, event_callbacks=event_callbacks,
            qos_overriding_options=qos_overriding_options, raw=raw)
