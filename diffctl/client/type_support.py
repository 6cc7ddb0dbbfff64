"""rclpy.type_support: checks that a class is a generated message or service type (its type support loads)."""

from __future__ import annotations

from typing import Any

from diffctl.client.exceptions import NoTypeSupportImportedException


def check_for_type_support(msg_or_srv_type: Any) -> None:
    try:
        support = msg_or_srv_type.__class__._TYPE_SUPPORT
    except AttributeError as e:
        # rclpy's hint for the usual cause: a ROS 1 class shadowing the ROS 2 one.
        e.args = (e.args[0] + " This might be a ROS 1 message type but it should be a ROS 2 message type."
                  " Make sure to source your ROS 2 workspace after your ROS 1 workspace.", *e.args[1:])
        raise
    if support is None:
        msg_or_srv_type.__class__.__import_type_support__()
    if msg_or_srv_type.__class__._TYPE_SUPPORT is None:
        raise NoTypeSupportImportedException()


def check_is_valid_msg_type(msg_type: Any) -> None:
    check_for_type_support(msg_type)
    meta = msg_type.__class__
    hooks = ("_CREATE_ROS_MESSAGE", "_CONVERT_FROM_PY", "_CONVERT_TO_PY", "_DESTROY_ROS_MESSAGE")
    if any(getattr(meta, h, None) is None for h in hooks):
        raise RuntimeError(f"The message type provided is not valid ({msg_type}), this might be a service or action")


def check_is_valid_srv_type(srv_type: Any) -> None:
    check_for_type_support(srv_type)
    if getattr(srv_type, "Request", None) is None or getattr(srv_type, "Response", None) is None:
        raise RuntimeError(f"The service type provided is not valid ({srv_type}), this might be a message or action")
