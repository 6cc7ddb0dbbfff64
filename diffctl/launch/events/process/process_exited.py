"""`ProcessExited`: a process ended."""

from ..._private.fields import field
from .running_process_event import RunningProcessEvent


class ProcessExited(RunningProcessEvent):
    """Emitted when the process is gone."""

    name = 'launch.events.process.ProcessExited'

    returncode = field('returncode', 'Its exit code; -N when signal N ended it.')

    def __init__(self, *, returncode: int, **kwargs) -> None:
        super().__init__(**kwargs)
        self._fields['returncode'] = returncode
