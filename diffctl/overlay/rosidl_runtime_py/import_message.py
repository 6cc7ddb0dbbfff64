"""rosidl_runtime_py.import_message."""

from diffctl.interfaces.runtime.names import import_message_from_namespaced_type  # noqa: F401
