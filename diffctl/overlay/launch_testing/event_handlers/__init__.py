"""`launch_testing.event_handlers` (diffctl/testing/stdout_ready_listener.py)."""

from .stdout_ready_listener import StdoutReadyListener

__all__ = ["StdoutReadyListener"]
