"""rosidl_runtime_py.get_interfaces."""

from diffctl.interfaces.runtime.index import (  # noqa: F401
    get_action_interfaces,
    get_interface_packages,
    get_interface_path,
    get_interfaces,
    get_message_interfaces,
    get_service_interfaces,
)
