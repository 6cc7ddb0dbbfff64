"""`launch_testing.util.proc_lookup` (diffctl/testing/proc_lookup.py)."""

from diffctl.testing.proc_lookup import NO_CMD_ARGS, NoMatchingProcessException
from diffctl.testing.proc_lookup import resolve_processes as resolveProcesses

__all__ = ["NO_CMD_ARGS", "NoMatchingProcessException", "resolveProcesses"]
