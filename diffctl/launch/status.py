"""The status table shown on SIGUSR1 or Enter: process, pid, state, restarts, uptime, exit code."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from diffctl.console import table


@dataclass(frozen=True)
class ProcessRow:
    name: str
    pid: int | None
    state: str
    restarts: int
    uptime_s: float | None
    exit_code: int | None


def _uptime(seconds: float | None) -> str:
    if seconds is None:
        return "-"
    if seconds < 60:
        return f"{seconds:.1f} s"
    minutes, secs = divmod(int(seconds), 60)
    hours, minutes = divmod(minutes, 60)
    return f"{hours}:{minutes:02d}:{secs:02d}" if hours else f"{minutes}:{secs:02d}"


class StatusView:
    def __init__(self, rows: list[ProcessRow], title: str = "processes") -> None:
        self.rows = rows
        self.title = title

    def __rich__(self) -> Any:
        return table(
            self.title,
            ["process", "pid", "state", "restarts", "uptime", "exit code"],
            [
                (
                    r.name,
                    r.pid if r.pid is not None else "-",
                    r.state,
                    r.restarts,
                    _uptime(r.uptime_s),
                    r.exit_code if r.exit_code is not None else "-",
                )
                for r in self.rows
            ],
        )
