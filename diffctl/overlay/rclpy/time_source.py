"""rclpy.time_source (diffctl: diffctl.client.node)."""

from diffctl.client.node import CLOCK_TOPIC, USE_SIM_TIME_NAME, TimeSource  # noqa: F401
