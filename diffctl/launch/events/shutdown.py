"""`Shutdown` (event): the launch should end."""

from __future__ import annotations

from ..event import Event


class Shutdown(Event):
    """Begins the shutdown of the whole launch; `due_to_sigint` when the user pressed Ctrl-C."""

    name = 'launch.events.Shutdown'

    def __init__(self, *, reason: str = 'reason not given', due_to_sigint: bool = False) -> None:
        self.__reason = reason
        self.__due_to_sigint = due_to_sigint

    @property
    def reason(self) -> str:
        """Why the launch is shutting down."""
        return self.__reason

    @property
    def due_to_sigint(self) -> bool:
        """Whether the shutdown comes from a SIGINT received by launch."""
        return self.__due_to_sigint
