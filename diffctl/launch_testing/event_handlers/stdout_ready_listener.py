"""StdoutReadyListener: run actions once a process prints a given text on stdout."""

from __future__ import annotations

from typing import Any

from diffctl.launch.event_handlers import OnProcessIO


class StdoutReadyListener(OnProcessIO):
    """An OnProcessIO handler for processes that say they are ready on stdout: when a chunk of
    `target_action`'s stdout (any process's, without one) contains `ready_txt`, `actions` are visited."""

    def __init__(self, *, target_action: Any = None, ready_txt: str, actions: list[Any]) -> None:
        self.__ready_txt = ready_txt
        self.__actions = actions
        super().__init__(target_action=target_action, on_stdout=self.__on_stdout)

    def __on_stdout(self, process_io: Any) -> list[Any] | None:
        return self.__actions if self.__ready_txt in process_io.text.decode() else None

    def describe(self) -> tuple[str, list[Any]]:
        return super().describe()[0], self.__actions
