"""Which processes a test names: an action object, a substring of the process name, and command arguments.

As launch_testing.util.proc_lookup: None is every process; an action matches by identity; a string matches
every process whose name contains it (`'talker'` finds `talker`, `talker-2`); `cmd_args` further keeps those
whose command line holds every one of them (`NO_CMD_ARGS`: no arguments at all).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

NO_CMD_ARGS = object()


class NoMatchingProcessException(Exception):
    pass


def process_name(action: Any) -> str:
    details = getattr(action, "process_details", None)
    if details:
        return str(details.get("name", ""))
    return ""


def _cmd(action: Any) -> list[str]:
    details = getattr(action, "process_details", None) or {}
    return list(details.get("cmd", []))


def _matches_args(action: Any, cmd_args: Any) -> bool:
    if cmd_args is None:
        return True
    args = _cmd(action)[1:]
    if cmd_args is NO_CMD_ARGS:
        return not args
    wanted = [cmd_args] if isinstance(cmd_args, str) else list(cmd_args)
    return all(a in args for a in wanted)


def resolve_processes(
    info_obj: Any, process: Any, cmd_args: Any = None, *, strict_proc_matching: bool = True
) -> list[Any]:
    """The actions `info_obj` (proc_info or proc_output) knows that `process`/`cmd_args` name."""
    known: Iterable[Any] = info_obj.processes()
    if process is None:
        return list(known)
    if not isinstance(process, str):
        return [process]
    matches = [a for a in known if process in process_name(a) and _matches_args(a, cmd_args)]
    if not matches:
        names = ", ".join(process_name(a) for a in info_obj.processes()) or "none"
        raise NoMatchingProcessException(
            f"Did not find any processes matching name '{process}' and args '{cmd_args}'. Processes: {names}"
        )
    if strict_proc_matching and len(matches) > 1:
        names = ", ".join(process_name(a) for a in matches)
        raise Exception(
            f"Found multiple processes matching name '{process}' and cmd_args '{cmd_args}'. Processes: [{names}]"
        )
    return matches
