"""What a launch file starts, for tests of the files diffctl ships and of users' workspaces.

`started(path, arguments)` runs the file on a LaunchService as `diffctl launch` would, with a spawner (launch's
injection point for process starting) that records each process's command line, environment and working
directory and starts `true` in its place (or `sleep`, for the processes `exits` says must keep running): the
launch's own logic — arguments, substitutions, includes, conditions, handlers — runs for real, nothing of the
robot starts. `required` tells whether a process's exit shuts the launch down.
"""

from __future__ import annotations

import asyncio
import dataclasses
import itertools
import os
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import yaml

from diffctl.launch import LaunchDescription, LaunchService
from diffctl.launch.actions import IncludeLaunchDescription
from diffctl.launch.events import Shutdown
from diffctl.launch.launch_description_sources import AnyLaunchDescriptionSource
from diffctl.supervision import PosixSpawner, SpawnRequest


@dataclasses.dataclass
class Started:
    name: str  # the process's label, `name-N`
    cmd: list[str]
    env: dict[str, str]
    cwd: str | None

    @property
    def base(self) -> str:
        return self.name.rsplit("-", 1)[0]

    @property
    def argv(self) -> list[str]:
        """The command line before `--ros-args`."""
        return self.cmd[: self.cmd.index("--ros-args")] if "--ros-args" in self.cmd else self.cmd

    def ros_args(self) -> list[str]:
        return self.cmd[self.cmd.index("--ros-args") + 1 :] if "--ros-args" in self.cmd else []

    def params(self) -> dict[str, Any]:
        """The node's parameters: its parameter files' `ros__parameters` (nested names dotted), then `-p`."""
        out: dict[str, Any] = {}
        args = self.ros_args()
        for flag, value in itertools.pairwise(args):
            if flag == "--params-file":
                for section in (yaml.safe_load(Path(value).read_text()) or {}).values():
                    _flatten(section.get("ros__parameters", {}), "", out)
            elif flag == "-p" and ":=" in value:
                key, text = value.split(":=", 1)
                out[key] = yaml.safe_load(text)
        return out


def _flatten(tree: dict[str, Any], prefix: str, out: dict[str, Any]) -> None:
    for key, value in tree.items():
        if isinstance(value, dict):
            _flatten(value, f"{prefix}{key}.", out)
        else:
            out[prefix + key] = value


@dataclasses.dataclass
class Run:
    started: list[Started]
    code: int
    shutdown_reason: str | None

    def one(self, base: str) -> Started:
        (found,) = [s for s in self.started if s.base == base]
        return found

    @property
    def required_exit(self) -> bool:
        """The launch was shut down by a process's exit (not by going idle)."""
        return self.shutdown_reason not in (None, "idle")


class _Recording(PosixSpawner):
    def __init__(self, exits: Callable[[str], bool]) -> None:
        super().__init__()
        self.exits = exits
        self.started: list[Started] = []
        self.last_start = time.monotonic()

    async def spawn(self, request: SpawnRequest, sink: Any) -> Any:
        env = dict(request.env or {})
        self.started.append(Started(request.name, list(request.cmd), env, request.cwd))
        self.last_start = time.monotonic()
        stand_in = ["true"] if self.exits(request.name.rsplit("-", 1)[0]) else ["sleep", "30"]
        return await super().spawn(dataclasses.replace(request, cmd=stand_in, shell=False), sink)


def started(
    path: Path,
    arguments: dict[str, str] | None = None,
    *,
    exits: Callable[[str], bool] = lambda name: True,
    timeout_s: float = 30.0,
) -> Run:
    """Run `path`; processes for which `exits(name)` is false keep running until nothing new has started for
    half a second, then the launch is shut down."""
    from diffctl.cli.launch import _use_diffctls_launch

    _use_diffctls_launch()  # as the launcher: launch files import diffctl's launch and launch_ros
    spawner = _Recording(exits)
    arguments = arguments or {}
    service = LaunchService(argv=[f"{k}:={v}" for k, v in arguments.items()], noninteractive=True, spawner=spawner)
    reasons: list[str] = []
    from diffctl.launch.actions import OpaqueFunction
    from diffctl.launch.event_handler import EventHandler

    service.context.register_event_handler(
        EventHandler(
            matcher=lambda e: isinstance(e, Shutdown),
            entities=OpaqueFunction(function=lambda context: reasons.append(str(context.locals.event.reason))),
        )
    )
    service.include_launch_description(
        LaunchDescription(
            [IncludeLaunchDescription(AnyLaunchDescriptionSource(str(path)), launch_arguments=arguments.items())]
        )
    )

    async def bounded() -> int:
        task = asyncio.ensure_future(service.run_async())
        deadline = time.monotonic() + timeout_s
        while not task.done():
            await asyncio.wait([task], timeout=0.1)
            quiet = time.monotonic() - spawner.last_start > 0.5
            if not task.done() and (quiet or time.monotonic() > deadline) and not reasons:
                pending = service.shutdown()
                if pending is not None:
                    await pending
        return task.result()

    saved = dict(os.environ)  # launch's environment actions change this process's, as in ros2/launch
    loop = asyncio.new_event_loop()
    try:
        code = loop.run_until_complete(bounded())
    finally:
        loop.close()
        os.environ.clear()
        os.environ.update(saved)
    return Run(spawner.started, code, reasons[0] if reasons else None)
