"""rclpy.type_description_service: a node's `~/get_type_description`, an ordinary service run by its executor
(as rclpy's) and answered by the bus node's type descriptions (the types this node's endpoints use)."""

from __future__ import annotations

from typing import Any

from diffctl.client.interfaces import cls
from diffctl.client.parameter_service import answer_with
from diffctl.client.qos import qos_profile_services_default

START_TYPE_DESCRIPTION_SERVICE_PARAM = "start_type_description_service"
SERVICE_TYPE = "type_description_interfaces/srv/GetTypeDescription"


class TypeDescriptionService:
    def __init__(self, node: Any) -> None:
        self._node = node
        self.service_name = f"{node.get_name()}/get_type_description"
        self._type_description_srv: Any = None
        # The bus node declared the (read-only) parameter and serves the types; the executor takes the requests.
        self.enabled = bool(node.get_parameter(START_TYPE_DESCRIPTION_SERVICE_PARAM).value)
        descriptions = getattr(node.bus_node, "_type_descriptions", None)
        if self.enabled and descriptions is not None:
            srv_type = cls(SERVICE_TYPE)
            self._type_description_srv = node.create_service(
                srv_type, self.service_name, answer_with(descriptions.handle, SERVICE_TYPE, srv_type.Response),
                qos_profile=qos_profile_services_default)

    def destroy(self) -> None:
        if self._type_description_srv is not None:
            self._node.destroy_service(self._type_description_srv)
            self._type_description_srv = None
