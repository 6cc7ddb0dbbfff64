"""Matchers selecting a process action by pid, name or executable."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ...actions.execute_process import ExecuteProcess


def _started_and(predicate: Callable[[dict], bool]) -> Callable[[ExecuteProcess], bool]:
    def matcher(action: ExecuteProcess) -> bool:
        details = action.process_details
        return details is not None and predicate(details)  # not started yet: matches nothing

    return matcher


def matches_pid(pid: int) -> Callable[[ExecuteProcess], bool]:
    """A matcher true for the process with this pid."""
    return _started_and(lambda details: details['pid'] == pid)


def matches_name(name: str) -> Callable[[ExecuteProcess], bool]:
    """A matcher true for the process with this final (unique) name."""
    return _started_and(lambda details: details['name'] == name)


def matches_executable(executable: str) -> Callable[[ExecuteProcess], bool]:
    """A matcher true when the command's first word ends with `executable` ('ls' matches '/usr/bin/ls')."""
    return _started_and(lambda details: details['cmd'][0].endswith(executable))
