"""`ProcessStderr`: bytes read from the process's standard error."""

from .process_io import ProcessIO


class ProcessStderr(ProcessIO):
    """A chunk read from the process's standard error (fd 2)."""

    name = 'launch.events.process.ProcessStderr'

    def __init__(self, *, text: bytes, **kwargs) -> None:
        super().__init__(text=text, fd=2, **kwargs)
