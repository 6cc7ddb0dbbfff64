"""rosidl_parser for code that imports it beside generated message classes (their `SLOT_TYPES`)."""
