"""rclpy.type_description_service: a node's `~/get_type_description`, an ordinary service run by its executor
(as rclpy's), answering for the types this node's endpoints use, matched by hash as rcl does."""

from __future__ import annotations

from typing import Any

from diffctl.client.interfaces import cls, deserialize
from diffctl.client.parameter import Parameter
from diffctl.client.qos import qos_profile_services_default
from diffctl.interfaces import types
from diffctl.interfaces.type_description import SERVICE_TYPE, describe

START_TYPE_DESCRIPTION_SERVICE_PARAM = "start_type_description_service"
_RCLPY_TEXT = "If enabled, start the ~/get_type_description service."
_RCLCPP_TEXT = "Start the ~/get_type_description service for this node."


class TypeDescriptionService:
    def __init__(self, node: Any) -> None:
        self._node = node
        self.service_name = f"{node.get_name()}/get_type_description"
        self._type_description_srv: Any = None
        descriptor = cls("rcl_interfaces/msg/ParameterDescriptor")(
            name=START_TYPE_DESCRIPTION_SERVICE_PARAM, type=Parameter.Type.BOOL.value,
            description=_RCLCPP_TEXT if getattr(node, "_rclcpp", False) else _RCLPY_TEXT, read_only=True)
        self.enabled = bool(node.declare_parameter(START_TYPE_DESCRIPTION_SERVICE_PARAM, True, descriptor).value)
        if self.enabled:
            self._type_description_srv = node._create_builtin_service(
                SERVICE_TYPE, self.service_name, self._answer, qos_profile=qos_profile_services_default)

    def _answer(self, request: Any, response: Any) -> Any:
        used = {types.type_hash(t): t for t in self._node.bus_node.used_types}
        typename = used.get(str(request.type_hash))
        if typename is None:
            answer: dict[str, Any] = {"successful": False, "failure_reason": "Type not currently in use by this node"}
        else:
            answer = {"successful": True, "type_description": describe(typename)}
            if request.include_type_sources:
                answer["type_sources"] = [{"type_name": typename, "encoding": "srv" if "/srv/" in typename else "msg",
                                           "raw_file_contents": types.definition(typename)}]
        # The description is plain data: through CDR it becomes the generated response class.
        data = types.serialize(types.response(SERVICE_TYPE, answer), SERVICE_TYPE + "_Response")
        return deserialize(data, type(response))

    def destroy(self) -> None:
        if self._type_description_srv is not None:
            self._node.destroy_service(self._type_description_srv)
            self._type_description_srv = None

