"""The status table shown on SIGUSR1 or Enter (process, pid, state, restarts, uptime, exit code), and the live
line's list of what the launch still waits for."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from diffctl.console import table

if TYPE_CHECKING:
    from diffctl.launch_legacy.supervisor import Supervisor


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
    """What the launch still waits for: gated actions, and processes handlers will start (for the live line)."""
    waiting = []
    for p in sup.pending:
        _, w = sup._gate_state(p.gate)
        waiting.append(f"{p.step.label} ({w.describe() if w else '…'})")
    engine = sup.engine
    for handler in engine.context.handlers:
        if (
            handler.kind not in ("exit", "start")
            or getattr(handler, "fired", False)
            or handler.exit_code not in (None, 0)
        ):
            continue
        started = [n for n in (_static_name(e) for e in handler.entities) if n]
        names = sorted(_target_names(handler, engine))
        if not started or not names:
            continue
        if any(sup.states[n].alive or sup.states[n].state == "not started" for n in names if n in sup.states):
            waiting.append(f"{', '.join(started)} (on {handler.kind} of {', '.join(names)})")
    return waiting


def _target_names(handler: Any, engine: Any) -> set[str]:
    names = set(getattr(handler, "_names", ()))
    for t in getattr(handler, "targets", ()):
        name = engine.origin_names.get(id(t))
        if name:
            names.add(name)
    return names


def _static_name(action: Any) -> str | None:
    """The name a process action will get, when it is written as plain text."""
    from diffctl.launch_legacy.process_actions import ExecuteProcess, Node
    from diffctl.launch_legacy.substitutions import TextSubstitution

    if not isinstance(action, ExecuteProcess):
        return None
    parts = action.name_subs
    if isinstance(action, Node) and parts is None:
        parts = action.name_parts if action.name_parts is not None else action.executable
    if parts and all(isinstance(p, TextSubstitution) for p in parts):
        return "".join(p.text for p in parts)
    return None


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
