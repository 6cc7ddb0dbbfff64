"""rclpy.utilities (diffctl: diffctl.client.utilities)."""

from diffctl.client.duration import S_TO_NS  # noqa: F401
from diffctl.client.utilities import *  # noqa: F403
from diffctl.client.utilities import get_available_rmw_implementations  # noqa: F401
