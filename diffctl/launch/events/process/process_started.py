"""`ProcessStarted`: a process exists."""

from .running_process_event import RunningProcessEvent


class ProcessStarted(RunningProcessEvent):
    """Emitted once the process runs and its pid is known (which says nothing of it being ready)."""

    name = 'launch.events.process.ProcessStarted'

    def __init__(self, **kwargs) -> None:
        super().__init__(**kwargs)
