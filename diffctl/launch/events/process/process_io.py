"""`ProcessIO`: bytes on one of a process's standard streams."""

from ..._private.fields import field
from .running_process_event import RunningProcessEvent

_STDIN, _STDOUT, _STDERR = 0, 1, 2


class ProcessIO(RunningProcessEvent):
    """A chunk read from the process's stdout or stderr, or written to its stdin (`fd` 0, 1 or 2).

    Chunks are as the pipe gave them: a line may come in pieces, several lines in one.
    """

    name = 'launch.events.process.ProcessIO'

    text = field('text', 'The bytes.')

    def __init__(self, *, text: bytes, fd: int, **kwargs) -> None:
        super().__init__(**kwargs)
        self._fields.update(text=text, fd=fd)

    @property
    def from_stdin(self) -> bool:
        return self._fields['fd'] == _STDIN

    @property
    def from_stdout(self) -> bool:
        return self._fields['fd'] == _STDOUT

    @property
    def from_stderr(self) -> bool:
        return self._fields['fd'] == _STDERR
