"""A node's `<name>/get_logger_levels` and `<name>/set_logger_levels` services (enable_logger_service=True)."""

from __future__ import annotations

from typing import Any

from diffctl.client import ros_logging
from diffctl.client.interfaces import cls
from diffctl.client.qos import qos_profile_services_default


class LoggingService:
    def __init__(self, node: Any) -> None:
        name = node.get_name()
        node.create_service(cls("rcl_interfaces/srv/GetLoggerLevels"), f"{name}/get_logger_levels",
                            self._get_logger_levels, qos_profile=qos_profile_services_default)
        node.create_service(cls("rcl_interfaces/srv/SetLoggerLevels"), f"{name}/set_logger_levels",
                            self._set_logger_levels, qos_profile=qos_profile_services_default)

    def _get_logger_levels(self, request: Any, response: Any) -> Any:
        level_cls = cls("rcl_interfaces/msg/LoggerLevel")
        response.levels = [level_cls(name=n, level=int(ros_logging.get_logger_level(n))) for n in request.names]
        return response

    def _set_logger_levels(self, request: Any, response: Any) -> Any:
        result_cls = cls("rcl_interfaces/msg/SetLoggerLevelsResult")
        results = []
        for level in request.levels:
            result = result_cls(successful=False)
            try:
                ros_logging.set_logger_level(level.name, level.level, detailed_error=True)
                result.successful = True
            except ValueError:
                result.reason = "Failed reason: Invalid logger level."
            results.append(result)
        response.results = results
        return response
