"""rosidl_runtime_py.set_message."""

from diffctl.interfaces.runtime.set_message import set_message_fields  # noqa: F401
