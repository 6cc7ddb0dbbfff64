"""`ProcessIO`: data on one of a process's standard streams."""

from .running_process_event import RunningProcessEvent


class ProcessIO(RunningProcessEvent):
    """A chunk of bytes read from (or for) a process's stdin (fd 0), stdout (1) or stderr (2)."""

    name = 'launch.events.process.ProcessIO'

    def __init__(self, *, text: bytes, fd: int, **kwargs) -> None:
        super().__init__(**kwargs)
        self.__text = text
        self.__fd = fd

    @property
    def text(self) -> bytes:
        """The bytes, as read (not necessarily whole lines)."""
        return self.__text

    @property
    def from_stdin(self) -> bool:
        return self.__fd == 0

    @property
    def from_stdout(self) -> bool:
        return self.__fd == 1

    @property
    def from_stderr(self) -> bool:
        return self.__fd == 2
