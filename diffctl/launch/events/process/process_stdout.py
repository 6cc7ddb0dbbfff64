"""`ProcessStdout`: bytes read from the process's standard output."""

from .process_io import ProcessIO


class ProcessStdout(ProcessIO):
    """A chunk read from the process's standard output (fd 1)."""

    name = 'launch.events.process.ProcessStdout'

    def __init__(self, *, text: bytes, **kwargs) -> None:
        super().__init__(text=text, fd=1, **kwargs)
