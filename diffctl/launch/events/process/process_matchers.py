"""Predicates choosing process actions by pid, unique name or executable (for `process_matcher`)."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ...actions.execute_process import ExecuteProcess


def _on_details(test: Callable[[dict[str, Any]], bool]) -> Callable[[ExecuteProcess], bool]:
    # an action not executed yet has no details: no such predicate chooses it
    def choose(action: ExecuteProcess) -> bool:
        details = action.process_details
        return False if details is None else test(details)

    return choose


def matches_pid(pid: int) -> Callable[[ExecuteProcess], bool]:
    """True for the action whose process has this pid."""
    return _on_details(lambda details: details['pid'] == pid)


def matches_name(name: str) -> Callable[[ExecuteProcess], bool]:
    """True for the action whose process has this unique name ('talker-1')."""
    return _on_details(lambda details: details['name'] == name)


def matches_executable(executable: str) -> Callable[[ExecuteProcess], bool]:
    """True when the command's first word ends with `executable` ('ls' chooses '/usr/bin/ls')."""
    return _on_details(lambda details: details['cmd'][0].endswith(executable))
