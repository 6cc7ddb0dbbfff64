"""rosidl_runtime_py.utilities."""

from diffctl.interfaces.runtime.names import (  # noqa: F401
    get_action,
    get_action_namespaced_type,
    get_interface,
    get_message,
    get_message_namespaced_type,
    get_namespaced_type,
    get_service,
    get_service_namespaced_type,
    is_action,
    is_message,
    is_service,
)
