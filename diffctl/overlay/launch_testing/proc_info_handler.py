"""`launch_testing.proc_info_handler` (diffctl/testing/handlers.py)."""

from diffctl.testing.handlers import ActiveProcInfoHandler, ProcInfoHandler

__all__ = ["ActiveProcInfoHandler", "ProcInfoHandler"]
