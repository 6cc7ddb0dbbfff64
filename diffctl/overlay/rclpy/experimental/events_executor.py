"""rclpy.experimental.events_executor (diffctl: diffctl.client.experimental)."""

import rclpy.executors  # noqa: F401  (as rclpy's module imports it)
from diffctl.client.experimental import EventsExecutor  # noqa: F401
