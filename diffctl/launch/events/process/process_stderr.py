"""`ProcessStderr`: data on a process's stderr."""

from .process_io import ProcessIO


class ProcessStderr(ProcessIO):
    """A chunk of bytes on the process's stderr."""

    name = 'launch.events.process.ProcessStderr'

    def __init__(self, *, text: bytes, **kwargs) -> None:
        super().__init__(text=text, fd=2, **kwargs)
