"""Starting and ending the processes a launch runs, so that none outlives it.

The launch core (`ExecuteLocal`) asks a `Spawner` for each process; the default `PosixSpawner` puts every
child in a process group of its own, reports its output as it is read and its exit as soon as it happens
(a pidfd on the asyncio loop), signals whole groups, and at the end of a launch ends every group still
alive (SIGTERM, then SIGKILL, each step logged). Other spawners (a fork server, a guard process) implement
the same interface and are handed to `LaunchService(spawner=...)`.
"""

from .spawner import ChildProcess, OutputSink, PosixSpawner, Spawner, SpawnRequest

__all__ = ['ChildProcess', 'OutputSink', 'PosixSpawner', 'SpawnRequest', 'Spawner']
