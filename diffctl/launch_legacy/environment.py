"""What a launch's children start with: their default environment and the run's log directory.

Kept free of the engine's imports: the launcher computes both before it imports anything else, so the fork
server (fork_server.py) can start at once, in exactly the environment its components will get.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path


def with_tool_path(env: dict[str, str]) -> dict[str, str]:
    """`env` with this interpreter's bin directory first on PATH.

    `$(command 'xacro …')`, `$(find-exec)` and the children find the venv's `xacro` and `diffctl` even when
    the venv is not activated (the launcher was started as .venv/bin/diffctl).
    """
    tools = str(Path(sys.executable).parent)
    parts = [p for p in env.get("PATH", "").split(os.pathsep) if p]
    if tools not in parts:
        env["PATH"] = os.pathsep.join([tools, *parts])
    return env


def child_env(env: dict[str, str]) -> dict[str, str]:
    """A child's final environment: line-buffered output from every Python child."""
    return {**env, "PYTHONUNBUFFERED": "1"}


def default_child_env(env: dict[str, str]) -> dict[str, str]:
    """The environment of a child that sets no variables of its own, when the launcher runs in `env`."""
    return child_env(with_tool_path(dict(env)))


def default_log_dir() -> Path:
    """ROS's layout: $ROS_LOG_DIR, else $ROS_HOME/log, else ~/.ros/log; one directory per run."""
    base = os.environ.get("ROS_LOG_DIR")
    root = Path(base) if base else Path(os.environ.get("ROS_HOME") or Path.home() / ".ros") / "log"
    stamp = time.strftime("%Y-%m-%d-%H-%M-%S") + f"-{int(time.time() * 1e6) % 1000000:06d}"
    host = os.uname().nodename.split(".")[0]
    return root / f"{stamp}-{host}-{os.getpid()}"
