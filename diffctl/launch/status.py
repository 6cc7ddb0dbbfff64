"""The status table shown on SIGUSR1 or Enter (process, pid, state, restarts, uptime, exit code), and the live
line's list of what the launch still waits for."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from diffctl.console import table
from diffctl.launch.plan import StartProcess

if TYPE_CHECKING:
    from diffctl.launch.supervisor import Supervisor


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


def awaited(sup: Supervisor) -> list[str]:
    """What the launch still waits for: gated steps, and processes handlers will start (for the live line)."""
    waiting = []
    for p in sup.pending:
        _, w = sup._gate_state(p.gate)
        what = p.step.spec.name if isinstance(p.step, StartProcess) else "step"
        waiting.append(f"{what} ({w.describe() if w else '…'})")
    for handler in sup.handlers:
        starts = any(isinstance(s, StartProcess) for s in handler.steps)
        if (
            starts
            and handler.event in ("exit", "start")
            and id(handler) not in sup.fired
            and handler.exit_code in (None, 0)
            and handler.targets
        ):
            names = [t.name for t in handler.targets if t.name]
            if any(sup.states[n].alive or sup.states[n].state == "not started" for n in names if n in sup.states):
                started = [s.spec.name for s in handler.steps if isinstance(s, StartProcess)]
                waiting.append(f"{', '.join(started)} (on {handler.event} of {', '.join(names)})")
    return waiting


def process_rows(sup: Supervisor) -> list[ProcessRow]:
    now = sup.now()
    return [
        ProcessRow(
            name,
            st.child.pid if st.child else None,
            st.state,
            st.restarts,
            now - st.started_at if st.child and st.started_at is not None else None,
            st.exit_code,
        )
        for name, st in sup.states.items()
    ]
