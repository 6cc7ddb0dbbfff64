"""rclpy.parameter_service.ParameterService: a node's six parameter services as ordinary rclpy services.

As in rclpy, the executor answers them (in the node's default callback group), so nothing is answered before
the node spins and a subclass has declared its parameters; the answers themselves are the bus's
(`diffctl.bus.parameter_services`, rclcpp's semantics), shared with diffctl's own nodes.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from diffctl.bus.parameter_services import RCL, SERVICES
from diffctl.client.interfaces import cls, deserialize
from diffctl.client.qos import qos_profile_parameters
from diffctl.interfaces import types


class ParameterService:
    def __init__(self, node: Any) -> None:
        bus_services = node.bus_node._parameter_services
        name = node.get_name()
        self._services = []
        for short, srv in SERVICES.items():
            srv_type = cls(RCL + srv)
            callback = answer_with(bus_services.handlers[short], RCL + srv, srv_type.Response)
            self._services.append(node.create_service(srv_type, f"{name}/{short}", callback,
                                                      qos_profile=qos_profile_parameters))


def answer_with(handler: Callable[[Any], dict[str, Any]], typename: str,
                response_cls: Any) -> Callable[[Any, Any], Any]:
    """An rclpy service callback answering with a bus handler's response (a dict of the response's fields)."""
    def callback(request: Any, _response: Any) -> Any:
        answer = types.serialize(types.response(typename, handler(request)), typename + "_Response")
        return deserialize(answer, response_cls)

    return callback
