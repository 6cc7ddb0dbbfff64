"""`launch_testing.util` (diffctl/testing/tools.py, proc_lookup.py)."""

from diffctl.testing.proc_lookup import NO_CMD_ARGS, NoMatchingProcessException
from diffctl.testing.proc_lookup import resolve_processes as resolveProcesses
from diffctl.testing.tools import KeepAliveProc

from . import proc_lookup  # noqa: F401

__all__ = ["NO_CMD_ARGS", "KeepAliveProc", "NoMatchingProcessException", "resolveProcesses"]
