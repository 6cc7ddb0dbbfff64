"""`RunningProcessEvent`: what every event about one process carries."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..._private.fields import field
from ...event import Event

if TYPE_CHECKING:
    from ...actions.execute_process import ExecuteProcess


class RunningProcessEvent(Event):
    """The process's action, its unique name, and the command, folder, environment and pid it runs with.

    cmd, cwd and env are as started, substitutions performed (env None: the launch's environment).
    """

    name = 'launch.events.process.RunningProcessEvent'

    action = field('action', 'The action running the process.')
    execute_process_action = field('action', 'The action running the process (its older name).')
    process_name = field('name', "The name of this process, unique in the launch ('talker-1').")
    cmd = field('cmd', 'The command line.')
    cwd = field('cwd', 'The working folder, or None.')
    env = field('env', 'The environment, or None.')
    pid = field('pid', 'The process id.')

    def __init__(
        self,
        *,
        action: ExecuteProcess,
        name: str,
        cmd: list[str],
        cwd: str | None,
        env: dict[str, str] | None,
        pid: int,
    ) -> None:
        super().__init__()
        self._fields = {'action': action, 'name': name, 'cmd': cmd, 'cwd': cwd, 'env': env, 'pid': pid}
