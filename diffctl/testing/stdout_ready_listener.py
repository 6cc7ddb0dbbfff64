"""launch_testing's StdoutReadyListener: run actions when a process prints a given text on stdout."""

from __future__ import annotations

from typing import Any

from diffctl.launch_legacy.event_handlers import OnProcessIO


class StdoutReadyListener(OnProcessIO):
    def __init__(self, *, target_action: Any = None, ready_txt: str, actions: list[Any]) -> None:
        self._ready_txt = ready_txt
        self._actions = actions
        super().__init__(target_action=target_action, on_stdout=self._on_stdout)

    def _on_stdout(self, event: Any) -> list[Any] | None:
        text = event.text.decode(errors="replace") if isinstance(event.text, bytes) else str(event.text)
        return self._actions if self._ready_txt in text else None
