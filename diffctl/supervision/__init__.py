"""Starting and ending the processes a launch runs, so that none outlives it.

The launch core (`ExecuteLocal`) asks a `Spawner` for each process; the default `PosixSpawner` puts every
child in a process group of its own, reports its output as it is read and its exit as soon as it happens
(a pidfd on the asyncio loop), signals whole groups, and at the end of a launch ends every group still
alive (SIGTERM, then SIGKILL, each step logged). Other spawners (a fork server, a guard process) implement
the same interface and are handed to `LaunchService(spawner=...)`.

The names are the spawner module's, imported on first use: the fork server (`python -m
diffctl.supervision.zygote`) runs this file first, and what it imports every component inherits — the
spawner's asyncio, ssl and concurrent.futures, which no component uses.
"""

from __future__ import annotations

TYPE_CHECKING = False  # typing unimported: the launcher reads this package before its fork server's exec
if TYPE_CHECKING:
    from typing import Any

__all__ = ['ChildProcess', 'OutputSink', 'PosixSpawner', 'SpawnRequest', 'Spawner']


def __getattr__(name: str) -> Any:
    if name in __all__:
        from . import spawner

        return getattr(spawner, name)
    raise AttributeError(f'module {__name__!r} has no attribute {name!r}')
