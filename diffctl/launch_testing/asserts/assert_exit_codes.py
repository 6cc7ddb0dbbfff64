"""Exit-code assertions on proc_info (PYTEST_DONT_REWRITE)."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from ..util import resolveProcesses

EXIT_OK = 0
EXIT_SIGINT = 130  # 128 + the signal: how a shell reports a process killed by it
EXIT_SIGQUIT = 131
EXIT_SIGKILL = 137
EXIT_SIGSEGV = 139
EXIT_FORCED = 1  # what Windows gives a process stopped from outside


def assertExitCodes(proc_info: Any, allowable_exit_codes: Iterable[int] = (EXIT_OK,), process: Any = None,
                    cmd_args: Any = None, *, strict_proc_matching: bool = True) -> None:
    """Every process `process` names (all of them by default) exited with one of `allowable_exit_codes`."""
    allowed = list(allowable_exit_codes)
    for code in allowed:
        if not isinstance(code, int):
            raise AssertionError(f"Provided exit code {code} is not an int")
    for action in resolveProcesses(proc_info, process=process, cmd_args=cmd_args,
                                   strict_proc_matching=strict_proc_matching):
        event = proc_info[action]
        if event.returncode not in allowed:
            raise AssertionError(f"Proc {event.process_name} exited with code {event.returncode}")
