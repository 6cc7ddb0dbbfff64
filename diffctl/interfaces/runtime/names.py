"""Interfaces by name (`pkg/msg/T`, `pkg/T`) and rosidl_parser's NamespacedType, as rosidl_runtime_py finds them."""

from __future__ import annotations

import importlib
import warnings
from typing import Any

from diffctl.interfaces.definition import NamespacedType


def import_message_from_namespaced_type(message_type: Any) -> Any:
    """The class a NamespacedType names (an action's FeedbackMessage is reached through its action)."""
    if not isinstance(message_type, NamespacedType) and hasattr(message_type, "value_type"):
        message_type = message_type.value_type
        warnings.warn("Passing objects containing a NamespacedType is deprecated, please pass a NamespacedType "
                      "object directly", DeprecationWarning, stacklevel=2)
    module = importlib.import_module(".".join(message_type.namespaces))
    if message_type.name.endswith("_FeedbackMessage"):
        action, name = message_type.name.rsplit("_", 1)
        return getattr(getattr(module, action).Impl, name)
    return getattr(module, message_type.name)


def _namespaced(identifier: str, default_namespace: str | None = None) -> NamespacedType:
    parts = identifier.split("/")
    namespaces = parts[:-1]
    if len(namespaces) == 1 and default_namespace is not None:
        namespaces.append(default_namespace)
    return NamespacedType(namespaces, parts[-1])


def get_namespaced_type(identifier: str) -> NamespacedType:
    return _namespaced(identifier)


def get_message_namespaced_type(identifier: str) -> NamespacedType:
    return _namespaced(identifier, "msg")


def get_service_namespaced_type(identifier: str) -> NamespacedType:
    return _namespaced(identifier, "srv")


def get_action_namespaced_type(identifier: str) -> NamespacedType:
    return _namespaced(identifier, "action")


def is_message(interface: Any) -> bool:
    return hasattr(interface, "SLOT_TYPES")


def is_service(interface: Any) -> bool:
    return hasattr(interface, "Request") and hasattr(interface, "Response")


def is_action(interface: Any) -> bool:
    return hasattr(interface, "Goal") and hasattr(interface, "Result") and hasattr(interface, "Feedback")


def get_interface(identifier: str) -> Any:
    return import_message_from_namespaced_type(get_namespaced_type(identifier))


def get_message(identifier: str) -> Any:
    interface = import_message_from_namespaced_type(get_message_namespaced_type(identifier))
    if not is_message(interface):
        raise ValueError(f"Expected the full name of a message, got '{identifier}'")
    return interface


def get_service(identifier: str) -> Any:
    interface = import_message_from_namespaced_type(get_service_namespaced_type(identifier))
    if not is_service(interface):
        raise ValueError(f"Expected the full name of a service, got '{identifier}'")
    return interface


def get_action(identifier: str) -> Any:
    interface = import_message_from_namespaced_type(get_action_namespaced_type(identifier))
    if not is_action(interface):
        raise ValueError(f"Expected the full name of an action, got '{identifier}'")
    return interface
