"""launch_testing.event_handlers."""

from .stdout_ready_listener import StdoutReadyListener

__all__ = ["StdoutReadyListener"]
