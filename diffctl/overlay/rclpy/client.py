"""rclpy.client (diffctl: diffctl.client.client)."""

from typing import TypeVar

from diffctl.client.client import *  # noqa: F403
from diffctl.client.service_introspection import ServiceIntrospectionState  # noqa: F401

SrvType = TypeVar("SrvType")
SrvTypeRequest = TypeVar("SrvTypeRequest")
SrvTypeResponse = TypeVar("SrvTypeResponse")
