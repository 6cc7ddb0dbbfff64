"""`ProcessStdin`: bytes written to the process's standard input."""

from .process_io import ProcessIO


class ProcessStdin(ProcessIO):
    """A chunk written to the process's standard input (fd 0)."""

    name = 'launch.events.process.ProcessStdin'

    def __init__(self, *, text: bytes, **kwargs) -> None:
        super().__init__(text=text, fd=0, **kwargs)
