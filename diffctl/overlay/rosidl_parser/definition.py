"""rosidl_parser.definition's type objects, from diffctl.client.messages.definition."""

from diffctl.client.messages import definition as _definition

globals().update({k: v for k, v in vars(_definition).items() if not k.startswith("__") and k != "annotations"})
