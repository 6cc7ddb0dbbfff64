"""rosidl_parser.definition's type objects, from diffctl.interfaces.definition."""

from diffctl.interfaces import definition as _definition

globals().update({k: v for k, v in vars(_definition).items() if not k.startswith("__") and k != "annotations"})
