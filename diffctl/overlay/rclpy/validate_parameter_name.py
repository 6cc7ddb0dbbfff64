"""rclpy.validate_parameter_name (diffctl: diffctl.client.node_parameters)."""

from diffctl.client.node_parameters import validate_parameter_name  # noqa: F401
