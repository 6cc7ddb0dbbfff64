"""rclpy.experimental (diffctl: diffctl.client.experimental)."""

from .events_executor import EventsExecutor  # noqa: F401
