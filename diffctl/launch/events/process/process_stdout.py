"""`ProcessStdout`: data on a process's stdout."""

from .process_io import ProcessIO


class ProcessStdout(ProcessIO):
    """A chunk of bytes on the process's stdout."""

    name = 'launch.events.process.ProcessStdout'

    def __init__(self, *, text: bytes, **kwargs) -> None:
        super().__init__(text=text, fd=1, **kwargs)
