"""Fixtures for the visualizer: a running `diffctl viz` on a free port, and the fake robot feeding it."""

from __future__ import annotations

import re
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
URL_RE = re.compile(r"open (http://[^\s/]+)/\?token=(\S+)")


@dataclass
class VizProcess:
    proc: subprocess.Popen
    base: str  # http://127.0.0.1:PORT
    token: str
    lines: list[str] = field(default_factory=list)

    @property
    def url(self) -> str:
        return f"{self.base}/?token={self.token}"

    @property
    def ws_url(self) -> str:
        return self.base.replace("http://", "ws://") + "/ws"

    @property
    def host_port(self) -> str:
        return self.base.removeprefix("http://")

    def output(self) -> str:
        return "".join(self.lines)


def _pump(proc: subprocess.Popen, lines: list[str]) -> None:
    for line in proc.stdout:  # type: ignore[union-attr]
        lines.append(line)


def wait_line(lines: list[str], pattern: re.Pattern[str] | str, proc: subprocess.Popen, timeout_s: float = 15.0):
    rx = re.compile(pattern) if isinstance(pattern, str) else pattern
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        for line in list(lines):
            m = rx.search(line)
            if m:
                return m
        if proc.poll() is not None:
            time.sleep(0.2)  # let the pump drain the last lines
            raise AssertionError(f"process exited {proc.returncode} before {rx.pattern!r}:\n{''.join(lines)}")
        time.sleep(0.05)
    raise AssertionError(f"no {rx.pattern!r} within {timeout_s} s:\n{''.join(lines)}")


def _start_with_url(procs, *args: str, timeout_s: float = 15.0) -> VizProcess:
    """`diffctl ARGS…`, once it has printed the visualizer's URL."""
    p = procs.diffctl(*args)
    lines: list[str] = []
    threading.Thread(target=_pump, args=(p, lines), daemon=True).start()
    m = wait_line(lines, URL_RE, p, timeout_s)
    return VizProcess(p, m.group(1), m.group(2), lines)


@pytest.fixture
def fake_robot(router, procs) -> Iterator[subprocess.Popen]:
    p = procs.start([sys.executable, str(HERE / "fake_robot.py")])
    lines: list[str] = []
    threading.Thread(target=_pump, args=(p, lines), daemon=True).start()
    wait_line(lines, "^ready", p)
    yield p


@pytest.fixture
def viz(router, procs) -> VizProcess:
    return _start_with_url(procs, "viz", "--port", "0")


@pytest.fixture
def start_viz(router, procs):
    """`start_viz(*args)` → a VizProcess with those extra command-line arguments."""
    return lambda *args: _start_with_url(procs, "viz", "--port", "0", *args)


@pytest.fixture
def launch_sim_control(router, procs, tmp_path: Path):
    """`launch_sim_control()` → the whole tutorial graph, its visualizer on a free port."""
    return lambda: _start_with_url(
        procs, "launch", "sim_control", "viz_port:=0", "--log-dir", str(tmp_path / "log"), timeout_s=60
    )
