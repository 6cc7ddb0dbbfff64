"""rosidl_runtime_py.convert."""

from diffctl.interfaces.runtime.convert import (  # noqa: F401
    get_message_slot_types,
    message_to_csv,
    message_to_ordereddict,
    message_to_yaml,
)
