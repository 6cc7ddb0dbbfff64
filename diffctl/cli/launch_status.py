"""What `diffctl launch` keeps of its processes: the status table it prints on Enter or SIGUSR1 (process, pid,
state, restarts, uptime, exit code; and once, how long the start-up took), and a log file per process.
"""

from __future__ import annotations

import os
import sys
import time
from dataclasses import dataclass
from typing import Any

from diffctl.launch.event_handler import BaseEventHandler
from diffctl.launch.events import Shutdown
from diffctl.launch.events.process import ProcessExited, ProcessIO, ProcessStarted


@dataclass
class Row:
    name: str
    pid: int | None = None
    state: str = "running"
    restarts: int = -1
    started_at: float | None = None
    exit_code: int | None = None


# The start-up is over once this long passes without a process starting.
SETTLED_S = 0.3


class ProcessTable(BaseEventHandler):
    """One row per process of the launch, kept from its start and exit events; says once how long the
    start-up took (`all N processes started in T ms`, from the launch's start to the last start before a
    quiet `SETTLED_S`, or before the launch ended by itself)."""

    def __init__(self) -> None:
        super().__init__(matcher=lambda e: isinstance(e, (ProcessStarted, ProcessExited, Shutdown)))
        self.rows: dict[str, Row] = {}
        self.shutting_down = False
        self.began_at: float | None = None
        self.last_start_at: float | None = None
        self.settled = False

    def handle(self, event: Any, context: Any) -> None:
        super().handle(event, context)
        if isinstance(event, Shutdown):
            if event.reason == 'idle' and self.last_start_at is not None:
                # every process ended before a quiet SETTLED_S: the start-up ended with the last start
                self._maybe_settled(self.last_start_at)
            self.shutting_down = True
            return None
        row = self.rows.setdefault(event.process_name, Row(event.process_name))
        if isinstance(event, ProcessStarted):
            row.pid, row.state, row.started_at, row.exit_code = event.pid, "running", time.monotonic(), None
            row.restarts += 1
            self.last_start_at = row.started_at
            if not self.settled:
                context.asyncio_loop.call_later(SETTLED_S, self._maybe_settled, row.started_at)
        else:
            row.exit_code = event.returncode
            row.state = "stopped" if self.shutting_down else "exited" if event.returncode == 0 else "failed"
            row.started_at = None
        return None

    def _maybe_settled(self, started_at: float) -> None:
        if self.settled or self.shutting_down or started_at != self.last_start_at or self.began_at is None:
            return
        self.settled = True
        from diffctl.launch import logging as launch_logging

        running = sum(1 for r in self.rows.values() if r.restarts >= 0)
        took_ms = (started_at - self.began_at) * 1000
        launch_logging.get_logger("launch").info(f"all {running} processes started in {took_ms:.0f} ms")

    def renderable(self) -> Any:
        # rich is imported once a table is asked for: a launch that shows none never loads it
        from diffctl.console import table

        now = time.monotonic()
        return table(
            "processes",
            ["process", "pid", "state", "restarts", "uptime", "exit code"],
            [
                (
                    r.name,
                    r.pid if r.pid is not None else "-",
                    r.state,
                    max(r.restarts, 0),
                    _uptime(now - r.started_at) if r.started_at is not None else "-",
                    r.exit_code if r.exit_code is not None else "-",
                )
                for r in self.rows.values()
            ],
        )


def _uptime(seconds: float) -> str:
    if seconds < 60:
        return f"{seconds:.1f} s"
    minutes, secs = divmod(int(seconds), 60)
    hours, minutes = divmod(minutes, 60)
    return f"{hours}:{minutes:02d}:{secs:02d}" if hours else f"{minutes}:{secs:02d}"


def show(processes: ProcessTable, *, no_color: bool = False) -> None:
    """Print the table (on Enter or SIGUSR1); a closed screen (`| head`) stops nothing."""
    from diffctl.console import make_console

    console = make_console(no_color=no_color, width=None if sys.stdout.isatty() else 200)
    try:
        console.print(processes.renderable())
    except (OSError, SystemExit):
        pass


class ProcessLogFiles(BaseEventHandler):
    """Everything each process prints, in `<log_dir>/<process name>.log`, whatever its `output` says (launch
    itself puts a process's output in launch.log, or with `own_log` in files of its own)."""

    def __init__(self, log_dir: str) -> None:
        super().__init__(matcher=lambda e: isinstance(e, (ProcessIO, ProcessExited)))
        self.log_dir = log_dir
        self.files: dict[str, Any] = {}

    def handle(self, event: Any, context: Any) -> None:
        super().handle(event, context)
        name = event.process_name
        if isinstance(event, ProcessExited):
            return None
        file = self.files.get(name)
        if file is None:
            safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in name.strip("/")) or "process"
            try:
                file = self.files[name] = open(os.path.join(self.log_dir, f"{safe}.log"), "ab", buffering=0)  # noqa: SIM115
            except OSError:
                return None
        text = event.text if isinstance(event.text, bytes) else str(event.text).encode()
        try:
            file.write(text)
        except OSError:
            pass  # a full disk must not stop the launch
        return None

    def close(self) -> None:
        for file in self.files.values():
            file.close()
        self.files.clear()
