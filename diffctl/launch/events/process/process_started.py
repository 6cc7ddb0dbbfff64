"""`ProcessStarted`: a process began running."""

from .running_process_event import RunningProcessEvent


class ProcessStarted(RunningProcessEvent):
    """Emitted once the process exists (its pid is known)."""

    name = 'launch.events.process.ProcessStarted'

    def __init__(self, **kwargs) -> None:
        super().__init__(**kwargs)
