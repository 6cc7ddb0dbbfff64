"""How a launch ended, for `diffctl launch`'s exit code: which processes failed, and what shut the launch down.

ros2 launch exits 1 only when the launch itself raised. diffctl (the default `--exit-code diffctl`) also exits 1
when a required process failed (its exit, non-zero, shut the launch down), or when the launch ended by itself
with a process whose last exit was a failure. A process stopped by the shutdown does not count, nor does a
failure before a Ctrl-C. Any LaunchService user can register the same observer.
"""

from __future__ import annotations

from typing import Any

from diffctl.launch.event_handler import BaseEventHandler
from diffctl.launch.events import Shutdown
from diffctl.launch.events.process import ProcessExited, ProcessStarted

IDLE_REASON = "idle"


def describe_exit(code: int) -> str:
    """'exit code 3' / 'killed by SIGSEGV'."""
    import signal

    if code < 0:
        try:
            return f"killed by {signal.Signals(-code).name}"
        except ValueError:
            return f"killed by signal {-code}"
    return f"exit code {code}"


class LaunchOutcome(BaseEventHandler):
    """Registered first on a LaunchService's context; `failures()` after the run."""

    def __init__(self) -> None:
        super().__init__(matcher=lambda e: isinstance(e, (ProcessStarted, ProcessExited, Shutdown)))
        self.failed: dict[str, int] = {}  # process name → its last exit code, when that was a failure
        self.last_exit: tuple[str, int] | None = None
        self.shutdown_reason: str | None = None
        self.by_signal = False

    def handle(self, event: Any, context: Any) -> None:
        super().handle(event, context)
        if isinstance(event, Shutdown):
            if self.shutdown_reason is None:
                self.shutdown_reason = str(event.reason)
                self.by_signal = bool(event.due_to_sigint) or "SIG" in str(event.reason)
            return None
        if self.shutdown_reason is not None:
            return None  # stopped by the shutdown
        name = event.process_name
        if isinstance(event, ProcessStarted):
            self.failed.pop(name, None)  # a respawn: judged by how this run ends
        else:
            self.last_exit = (name, event.returncode)
            if event.returncode != 0:
                self.failed[name] = event.returncode
            else:
                self.failed.pop(name, None)
        return None

    def failures(self) -> list[str]:
        """Why the launch failed, in diffctl's terms (empty: it did not)."""
        if self.shutdown_reason is None or self.by_signal:
            return []
        if self.shutdown_reason == IDLE_REASON:
            if not self.failed:
                return []
            return ["failed: " + ", ".join(f"{n} ({describe_exit(c)})" for n, c in self.failed.items())]
        if self.last_exit is not None and self.last_exit[1] != 0 and self.last_exit[0] in self.failed:
            name, code = self.last_exit
            how = f"was {describe_exit(code)}" if code < 0 else f"ended with {describe_exit(code)}"
            return [f"required process {name!r} {how}"]
        return []
