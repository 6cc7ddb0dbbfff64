"""What `diffctl launch` does before it reads the launch file: its children's environment, its log directory
and its fork server, started as early as the command line allows.

The fork server's imports are the start-up's critical path (nothing is forked before they end), so the entry
point (`diffctl/__main__.py`) starts it before click and the commands are imported, from a reading of the
command line that knows only `launch`'s options (`early_start`). The `launch` command then takes that server
when click has read the same working directory options (`take_early`); any other command line, or one read
differently, gets the server the command starts itself, with the environment as it was before.
"""

from __future__ import annotations

import atexit
import os
import sys
from pathlib import Path

# typing is imported by nothing else before the fork server's exec, which waits for this module: 6 ms
TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

# `launch`'s options that take a value, and those of them the environment and the server depend on
VALUE_OPTIONS = ("--log-dir", "--workspace", "--output-default", "--exit-code", "--signal", "--process-names")
FLAGS = ("--no-color", "--no-router", "-d", "--debug")

_early: tuple[Path | None, Path | None, Path | None, Path, Any, dict[str, str]] | None = None


def prepare_environment(workspace_dir: Path | None) -> Path | None:
    """What every child and the launch file itself see: the workspace's packages and hooks, Jazzy's ROS_*
    variables, this interpreter's tools first on PATH (`$(command 'xacro …')` and children find the venv's
    `xacro` and `diffctl` unactivated), and line-buffered Python output."""
    from diffctl.workspace import find_workspace, use_in_children

    workspace = find_workspace(explicit=workspace_dir)
    use_in_children(workspace)
    tools = str(Path(sys.executable).parent)
    parts = [p for p in os.environ.get("PATH", "").split(os.pathsep) if p]
    if tools not in parts:
        os.environ["PATH"] = os.pathsep.join([tools, *parts])
    os.environ["PYTHONUNBUFFERED"] = "1"  # children's output line by line, as the launch shows it
    return workspace


def default_log_dir() -> Path:
    """ROS's layout: $ROS_LOG_DIR, else $ROS_HOME/log, else ~/.ros/log; one directory per run."""
    import time

    base = os.environ.get("ROS_LOG_DIR")
    root = Path(base) if base else Path(os.environ.get("ROS_HOME") or Path.home() / ".ros") / "log"
    stamp = time.strftime("%Y-%m-%d-%H-%M-%S") + f"-{int(time.time() * 1e6) % 1000000:06d}"
    return root / f"{stamp}-{os.uname().nodename.split('.')[0]}-{os.getpid()}"


def start_fork_server(run_dir: Path) -> Any:
    """The fork server, started in the environment the launch's children will get (None when turned off)."""
    from diffctl.supervision import fork_server

    env = dict(os.environ, DIFFCTL_LOG_DIR=str(run_dir.resolve()))
    os.environ["DIFFCTL_LOG_DIR"] = env["DIFFCTL_LOG_DIR"]  # `diffctl bag record` without -o writes beside the logs
    if not fork_server.enabled(env):
        return None
    from diffctl.cli.fork_preload import SPEC

    return fork_server.ForkServer(env, preexec=fork_server.dies_with_launcher(), preload=SPEC)


def working_options(args: list[str]) -> tuple[Path | None, Path | None] | None:
    """(--workspace, --log-dir) of `launch ARGS…` when it runs a launch file; None when it only describes one
    (-s, -p), asks for help, or holds anything this reading is not sure of (click reads it then)."""
    values: dict[str, str] = {}
    positional = 0
    words = iter(args)
    for word in words:
        if word in ("--", "--ros-args") or word.startswith("--ros-args"):
            return None
        name, eq, value = word.partition("=")
        if name in VALUE_OPTIONS:
            if not eq:
                value = next(words, None)  # type: ignore[assignment]
                if value is None:
                    return None
            values[name] = value  # the last one wins, as click has it
        elif word in FLAGS:
            continue
        elif word.startswith("-"):
            return None  # -s, -p, -h, a cluster of short flags, a typo: click's to read
        else:
            positional += 1
    if positional == 0:
        return None
    workspace, log_dir = values.get("--workspace"), values.get("--log-dir")
    return (Path(workspace) if workspace else None), (Path(log_dir) if log_dir else None)


def early_start(argv: list[str]) -> None:
    """Start the fork server now when `argv` (the command line after the program) is `launch` running a file."""
    global _early
    if _early is not None or not argv or argv[0] != "launch":
        return
    options = working_options(argv[1:])
    if options is None:
        return
    workspace_dir, log_dir = options
    before = dict(os.environ)
    try:
        workspace = prepare_environment(workspace_dir)
        run_dir = log_dir or default_log_dir()
        server = start_fork_server(run_dir)
    except Exception:
        _restore(before)  # the command meets the same problem and reports it
        return
    _early = (workspace_dir, log_dir, workspace, run_dir, server, before)
    atexit.register(_discard)  # a command line click refuses ends here, its server with it


def take_early(workspace_dir: Path | None, log_dir: Path | None) -> tuple[Path | None, Path, Any] | None:
    """(workspace, run directory, fork server) prepared by `early_start` for these options, else None (and
    what it prepared for others undone)."""
    global _early
    if _early is None:
        return None
    early_workspace, early_log, workspace, run_dir, server, before = _early
    _early = None
    if (early_workspace, early_log) == (workspace_dir, log_dir):
        return workspace, run_dir, server
    if server is not None:
        server.close(kill=True)
    _restore(before)
    return None


def _discard() -> None:
    global _early
    if _early is not None and _early[4] is not None:
        _early[4].close(kill=True)
    _early = None


def _restore(environment: dict[str, str]) -> None:
    os.environ.clear()
    os.environ.update(environment)
