"""Finding the processes of a launch a test means: by action, by name (and command-line arguments), or all."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from diffctl.launch.actions import ExecuteLocal, ExecuteProcess

NO_CMD_ARGS = object()  # cmd_args=NO_CMD_ARGS: only a process started with no argument matches


class NoMatchingProcessException(Exception):
    """No process known to a proc_info / proc_output matches what a test asked for."""


class _Unresolvable(Exception):
    pass


class _NoContext:
    """Stands in for a launch context where none exists yet: any use of it means 'cannot tell'."""

    def __getattr__(self, name: str) -> Any:
        raise _Unresolvable(name)


def _describe(action: Any) -> str:
    """'name arg1 arg2' of a started process; of one not started yet, its command if it is plain text."""
    details = action.process_details
    if details:
        return " ".join([details["name"], *details["cmd"][1:]])
    if isinstance(action, ExecuteProcess):
        cmd = action.cmd
    elif isinstance(action, ExecuteLocal):
        cmd = action.process_description.cmd
    else:
        cmd = []
    try:
        return " ".join("".join(s.perform(_NoContext()) for s in part) for part in cmd)
    except _Unresolvable:
        return "Unknown - Process not launched yet"


def _known(info_obj: Any) -> list[Any]:
    return list(info_obj.processes())


def _args_match(action: Any, cmd_args: Iterable[str] | object | None) -> bool:
    args = action.process_details["cmd"][1:]
    if cmd_args is None:
        return True
    if cmd_args is NO_CMD_ARGS:
        return not args
    return all(a in args for a in cmd_args)  # type: ignore[union-attr]


def resolveProcesses(info_obj: Any, *, process: Any = None, cmd_args: Any = None,
                     strict_proc_matching: bool = True) -> list[Any]:
    """The ExecuteProcess actions of `info_obj` (a proc_info or proc_output) that `process` names.

    `process` is None (every process), an action, or a string contained in the process name; with a string,
    `cmd_args` (a list, a single string, or NO_CMD_ARGS) narrows the match, and `strict_proc_matching`
    refuses more than one match. Nothing matching raises NoMatchingProcessException."""
    known = _known(info_obj)
    if process is None:
        if not known:
            raise NoMatchingProcessException("No data recorded for any process")
        return known
    if isinstance(process, (ExecuteProcess, ExecuteLocal)):
        if any(p is process for p in known):
            return [process]
        raise NoMatchingProcessException(f"No data recorded for proc {_describe(process)}")
    if not isinstance(process, str):
        raise TypeError(f"proc argument must be 'ExecuteProcess' or 'str' not {type(process)}")
    if isinstance(cmd_args, str):
        cmd_args = [cmd_args]  # the old spelling: one argument as a plain string
    found = [p for p in known if process in p.process_details["name"] and _args_match(p, cmd_args)]
    everything = ", ".join(sorted(_describe(p) for p in known))
    if not found:
        raise NoMatchingProcessException(
            f"Did not find any processes matching name '{process}' and args '{cmd_args}'. Procs: {everything}"
        )
    if strict_proc_matching and len(found) > 1:
        raise Exception(
            f"Found multiple processes matching name '{process}' and cmd_args '{cmd_args}'. Procs: {everything}"
        )
    return found
