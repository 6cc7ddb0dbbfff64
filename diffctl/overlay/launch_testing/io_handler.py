"""`launch_testing.io_handler` (diffctl/testing/handlers.py)."""

from diffctl.testing.handlers import ActiveIoHandler, IoHandler

__all__ = ["ActiveIoHandler", "IoHandler"]
