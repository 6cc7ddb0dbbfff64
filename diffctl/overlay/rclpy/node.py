"""rclpy.node (diffctl: diffctl.client.node)."""

from typing import TypeVar

from diffctl.client.duration import S_TO_NS  # noqa: F401
from diffctl.client.exceptions import InvalidHandle  # noqa: F401
from diffctl.client.node import *  # noqa: F403
from diffctl.client.parameter import PARAMETER_SEPARATOR_STRING  # noqa: F401

# rclpy's node module imports these, so after `from rclpy.node import Node` they are attributes of `rclpy`
# (`rclpy.executors.…`, `rclpy.logging.…`) as programs expect; each is a thin name map over a module
# diffctl.client.node has already loaded.
from . import (  # noqa: F401
    callback_groups,
    client,
    clock,
    clock_type,
    duration,
    event_handler,
    executors,
    expand_topic_name,
    logging,
    logging_service,
    parameter_service,
    publisher,
    qos,
    qos_overriding_options,
    service,
    service_introspection,
    subscription,
    time,
    time_source,
    timer,
    topic_endpoint_info,
    type_description_service,
    type_hash,
    type_support,
    validate_full_topic_name,
    validate_namespace,
    validate_node_name,
    validate_parameter_name,
    validate_topic_name,
    waitable,
)
from .impl import logging_severity, rcutils_logger  # noqa: F401

HIDDEN_NODE_PREFIX = "_"
MsgType = TypeVar("MsgType")
SrvType = TypeVar("SrvType")
SrvTypeRequest = TypeVar("SrvTypeRequest")
SrvTypeResponse = TypeVar("SrvTypeResponse")
