"""launch_testing.util: process lookup and a process that keeps a launch up while tests run."""

from __future__ import annotations

import sys

from diffctl.launch.actions import ExecuteProcess

from .proc_lookup import NO_CMD_ARGS, NoMatchingProcessException, resolveProcesses

_IDLE_UNTIL_INTERRUPTED = """
import time
try:
    while True:
        time.sleep(3600)
except KeyboardInterrupt:
    pass
"""


def KeepAliveProc() -> ExecuteProcess:
    """A process that idles until it is interrupted: the launch of a test whose processes all end by
    themselves stays up (launch_test shuts it down when the tests are done)."""
    return ExecuteProcess(cmd=[sys.executable, "-c", _IDLE_UNTIL_INTERRUPTED])


__all__ = ["NO_CMD_ARGS", "KeepAliveProc", "NoMatchingProcessException", "resolveProcesses"]
