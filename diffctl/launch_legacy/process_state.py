"""What the supervisor keeps per process and the interfaces it is driven through (clock, process spawner).

Kept apart from supervisor.py so the state machine reads on its own; tests give fakes of `Clock` and
`Spawner`, loop.py the real ones.
"""

from __future__ import annotations

import signal
import time
from collections import deque
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Protocol

from diffctl.launch_legacy.plan import Gate, ProcessSpec, Step, Wait

if TYPE_CHECKING:
    from diffctl.launch_legacy.readiness import ProbePoller


class Clock(Protocol):
    def monotonic(self) -> float: ...


class SystemClock:
    def monotonic(self) -> float:
        return time.monotonic()


@dataclass(frozen=True)
class Child:
    pid: int
    pgid: int


class Spawner(Protocol):
    def spawn(self, name: str, argv: list[str], env: dict[str, str], cwd: str | None, interactive: bool) -> Child:
        """Start a process in a new process group; raises OSError when it cannot start."""

    def signal_group(self, child: Child, sig: int) -> bool:
        """Signal the child's process group; False when the group no longer exists."""

    def group_alive(self, child: Child) -> bool: ...

    def forget(self, child: Child) -> None:
        """The group is gone: stop guarding it."""


@dataclass
class ProcessState:
    spec: ProcessSpec
    state: str = "not started"
    child: Child | None = None
    lingering: Child | None = None  # leader exited, others of its group still alive
    starts: int = 0
    restarts: int = 0
    started_at: float | None = None
    exit_code: int | None = None
    tail: deque[str] = field(default_factory=lambda: deque(maxlen=5))
    seen_patterns: set[str] = field(default_factory=set)
    stop_timers: list[Timer] = field(default_factory=list)

    @property
    def alive(self) -> bool:
        return self.child is not None or self.lingering is not None

    @property
    def respawns_left(self) -> bool:
        limit = self.spec.respawn_max_retries
        return self.spec.respawn and (limit < 0 or self.restarts < limit)


@dataclass
class Timer:
    callback: Callable[[], None]
    kind: str  # "timer" | "respawn" | "stop"
    cancelled: bool = False


@dataclass
class Pending:
    step: Step
    gate: Gate
    since: float


def describe_exit(code: int) -> str:
    if code < 0:
        try:
            return f"killed by {signal.Signals(-code).name}"
        except ValueError:
            return f"killed by signal {-code}"
    return f"exit code {code}"


def died(code: int) -> str:
    """'died with exit code 3' / 'was killed by SIGKILL' (not 'died with killed by …')."""
    return f"was {describe_exit(code)}" if code < 0 else f"died with {describe_exit(code)}"


def wait_state(w: Wait, states: Mapping[str, ProcessState], poller: ProbePoller | None) -> bool | str:
    """One readiness condition: True when met, False while it may still be met, or why it never will be."""
    if w.kind in ("topic", "service"):
        return poller is not None and poller.ready(w.kind, str(w.target))
    st = states.get(str(w.target))
    if st is None:
        return f"{w.target} is not a process of this launch"
    if w.kind == "started":
        if st.starts == 0 and st.state == "failed":
            return f"{w.target} could not start"
        return st.starts > 0
    finished = not st.alive and st.state in ("exited", "failed")
    if w.kind == "exited":
        if finished and st.exit_code == 0:
            return True
        if finished and st.state == "failed":
            return f"{w.target} {describe_exit(st.exit_code or 0)}"
        return False
    if w.pattern in st.seen_patterns:
        return True
    return f"{w.target} ended without printing /{w.pattern}/" if finished else False
