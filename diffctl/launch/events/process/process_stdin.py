"""`ProcessStdin`: data on a process's stdin."""

from .process_io import ProcessIO


class ProcessStdin(ProcessIO):
    """A chunk of bytes on the process's stdin."""

    name = 'launch.events.process.ProcessStdin'

    def __init__(self, *, text: bytes, **kwargs) -> None:
        super().__init__(text=text, fd=0, **kwargs)
