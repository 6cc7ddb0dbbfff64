"""`launch_testing.event_handlers.stdout_ready_listener` (diffctl/testing/stdout_ready_listener.py)."""

from diffctl.testing.stdout_ready_listener import StdoutReadyListener

__all__ = ["StdoutReadyListener"]
