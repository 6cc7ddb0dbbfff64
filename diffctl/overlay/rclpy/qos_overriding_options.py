"""rclpy.qos_overriding_options (diffctl: diffctl.client.qos_overriding_options)."""

from diffctl.client.exceptions import InvalidQosOverridesError  # noqa: F401
from diffctl.client.qos_overriding_options import *  # noqa: F403
from diffctl.client.qos_overriding_options import (  # noqa: F401  (private in rclpy, yet imported by packages)
    _declare_qos_parameters,
    _get_qos_policy_parameter,
)
