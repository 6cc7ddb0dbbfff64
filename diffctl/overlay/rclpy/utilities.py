"""rclpy.utilities (diffctl: diffctl.client.utilities)."""

from diffctl.client.utilities import *  # noqa: F403
