"""rclpy.parameter_service.ParameterService: a node's six parameter services as ordinary rclpy services.

As in rclpy, the executor answers them (in the node's default callback group), so nothing is answered before
the node spins and a subclass has declared its parameters. A request naming an undeclared (or, for
get_parameters, uninitialized) parameter gets an empty list back, as rclpy answers it.
"""

from __future__ import annotations

import weakref
from collections.abc import Callable
from typing import Any

from diffctl.client.exceptions import ParameterNotDeclaredException, ParameterUninitializedException
from diffctl.client.interfaces import cls
from diffctl.client.parameter import Parameter
from diffctl.client.qos import qos_profile_parameters

RCL = "rcl_interfaces/srv/"


class ParameterService:
    def __init__(self, node: Any) -> None:
        self._node_weak_ref = weakref.ref(node)
        name = node.get_name()
        for short, srv, callback in (
            ("describe_parameters", "DescribeParameters", self._describe),
            ("get_parameters", "GetParameters", self._get),
            ("get_parameter_types", "GetParameterTypes", self._get_types),
            ("list_parameters", "ListParameters", self._list),
            ("set_parameters", "SetParameters", self._set),
            ("set_parameters_atomically", "SetParametersAtomically", self._set_atomically),
        ):
            node._create_builtin_service(RCL + srv, f"{name}/{short}", callback, qos_profile=qos_profile_parameters)

    def _node(self) -> Any:
        node = self._node_weak_ref()
        if node is None:
            raise ReferenceError("Expected valid node weak reference")
        return node

    @staticmethod
    def _each(names: Any, get: Callable[[str], Any], missing: tuple[type, ...]) -> list[Any]:
        out = []
        for name in names:
            try:
                out.append(get(name))
            except missing:
                return []
        return out

    def _describe(self, request: Any, response: Any) -> Any:
        response.descriptors = self._each(request.names, self._node().describe_parameter,
                                          (ParameterNotDeclaredException,))
        return response

    def _get(self, request: Any, response: Any) -> Any:
        node = self._node()
        response.values = self._each(request.names, lambda n: node.get_parameter(n).get_parameter_value(),
                                     (ParameterNotDeclaredException, ParameterUninitializedException))
        return response

    def _get_types(self, request: Any, response: Any) -> Any:
        node = self._node()
        # Node.get_parameter_type gives an undeclared name (allow_undeclared_parameters) as the enum member
        response.types = self._each(request.names, lambda n: Parameter.Type(node.get_parameter_type(n)).value,
                                    (ParameterNotDeclaredException,))
        return response

    def _list(self, request: Any, response: Any) -> Any:
        try:
            response.result = self._node().list_parameters(list(request.prefixes), int(request.depth))
        except (TypeError, ValueError):
            response.result = cls("rcl_interfaces/msg/ListParametersResult")()
        return response

    def _set_one(self, parameters: list[Any]) -> Any:
        try:
            return self._node().set_parameters_atomically([Parameter.from_parameter_msg(p) for p in parameters])
        except ParameterNotDeclaredException as e:
            return cls("rcl_interfaces/msg/SetParametersResult")(successful=False, reason=str(e))

    def _set(self, request: Any, response: Any) -> Any:
        response.results = [self._set_one([p]) for p in request.parameters]
        return response

    def _set_atomically(self, request: Any, response: Any) -> Any:
        response.result = self._set_one(list(request.parameters))
        return response
