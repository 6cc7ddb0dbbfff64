"""Fixtures for the launch engine: a real launcher run that can never leak, and fakes for the supervisor.

Every launcher started here gets a unique DIFFCTL_TEST_TAG in its environment, which all its descendants
inherit; `tagged(tag)` finds any of them still alive (even orphans re-parented to init), and teardown
SIGKILLs them, so a failing test leaves nothing behind either.
"""

from __future__ import annotations

import io
import os
import re
import signal
import subprocess
import sys
import time
import uuid
from collections.abc import Iterator
from pathlib import Path

import psutil
import pytest

from diffctl.launch_legacy.loader import load
from diffctl.launch_legacy.output import Output
from diffctl.launch_legacy.plan import Plan
from diffctl.launch_legacy.process_state import Child
from diffctl.launch_legacy.resolver import resolve
from diffctl.launch_legacy.supervisor import Supervisor

DATA = Path(__file__).parent / "data"


def tagged(tag: str) -> list[psutil.Process]:
    """Every live process (zombies aside) whose environment carries this test's tag."""
    found = []
    for p in psutil.process_iter():
        try:
            if p.status() == psutil.STATUS_ZOMBIE:
                continue
            if p.environ().get("DIFFCTL_TEST_TAG") == tag:
                found.append(p)
        except (psutil.NoSuchProcess, psutil.AccessDenied, psutil.ZombieProcess):
            continue
    return found


class LaunchRun:
    """`diffctl launch …` as a real child, its output in a file, polled with timeouts."""

    def __init__(self, args: list[str], tmp: Path, env: dict[str, str] | None = None, cwd: Path | None = None) -> None:
        self.tag = uuid.uuid4().hex
        self.log_dir = tmp / f"logs-{self.tag[:8]}"
        self.out_path = tmp / f"launcher-{self.tag[:8]}.out"
        full_env = dict(os.environ, DIFFCTL_TEST_TAG=self.tag, **(env or {}))
        self._out = open(self.out_path, "w")  # noqa: SIM115
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "diffctl", "launch", *args, "--no-color", "--log-dir", str(self.log_dir)],
            stdout=self._out,
            stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
            env=full_env,
            start_new_session=True,
            cwd=cwd,
        )

    def text(self) -> str:
        return self.out_path.read_text()

    def wait_for(self, pattern: str, timeout_s: float = 10.0) -> re.Match[str]:
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            m = re.search(pattern, self.text(), re.MULTILINE)
            if m:
                return m
            if self.proc.poll() is not None:
                m = re.search(pattern, self.text(), re.MULTILINE)
                if m:
                    return m
                raise AssertionError(f"launcher exited ({self.proc.returncode}) before /{pattern}/:\n{self.text()}")
            time.sleep(0.02)
        raise AssertionError(f"no /{pattern}/ after {timeout_s} s:\n{self.text()}")

    def signal(self, sig: int) -> None:
        os.kill(self.proc.pid, sig)

    def wait(self, timeout_s: float = 15.0) -> int:
        try:
            return self.proc.wait(timeout_s)
        except subprocess.TimeoutExpired:
            raise AssertionError(f"launcher still running after {timeout_s} s:\n{self.text()}") from None

    def leftovers(self) -> list[psutil.Process]:
        return tagged(self.tag)

    def close(self) -> None:
        for p in [*self.leftovers()]:
            try:
                p.kill()
            except psutil.NoSuchProcess:
                pass
        try:
            os.killpg(self.proc.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
        self.proc.wait(5)
        self._out.close()


@pytest.fixture
def launch_run(tmp_path: Path) -> Iterator:
    runs: list[LaunchRun] = []

    def start(*args: str, env: dict[str, str] | None = None, cwd: Path | None = None) -> LaunchRun:
        run = LaunchRun(list(args), tmp_path, env, cwd)
        runs.append(run)
        return run

    try:
        yield start
    finally:
        for run in runs:
            run.close()


# ---- fakes for unit tests of the supervisor ------------------------------------------------------------------


class FakeClock:
    def __init__(self) -> None:
        self.t = 0.0

    def monotonic(self) -> float:
        return self.t


class FakeSpawner:
    """Records spawns and signals; a test ends processes with `exit(name, code)`."""

    def __init__(self) -> None:
        self.next_pid = 1000
        self.alive: set[int] = set()
        self.pids: dict[str, int] = {}
        self.spawned: list[tuple[float, str, list[str]]] = []
        self.envs: dict[str, dict[str, str]] = {}
        self.signals: list[tuple[float, str, str]] = []
        self.names: dict[int, str] = {}
        self.cannot_start: set[str] = set()
        self.dying: list[tuple[int, int]] = []
        self.ignore: dict[str, set[int]] = {}  # process name → signals it survives
        self.clock: FakeClock | None = None
        self.supervisor: Supervisor | None = None

    def spawn(self, name: str, argv: list[str], env: dict[str, str], cwd: str | None, interactive: bool) -> Child:
        if name in self.cannot_start:
            raise FileNotFoundError(2, "No such file or directory")
        pid = self.next_pid
        self.next_pid += 1
        self.alive.add(pid)
        self.pids[name] = pid
        self.names[pid] = name
        self.spawned.append((self.clock.t if self.clock else 0.0, name, argv))
        self.envs[name] = env
        return Child(pid, pid)

    def signal_group(self, child: Child, sig: int) -> bool:
        if child.pgid not in self.alive:
            return False
        name = self.names[child.pid]
        self.signals.append((self.clock.t if self.clock else 0.0, name, signal.Signals(sig).name))
        if sig != 0 and sig not in self.ignore.get(name, set()):
            self.dying.append((child.pid, -sig))  # delivered later, as a real SIGCHLD would be
        return True

    def deliver(self) -> None:
        while self.dying:
            pid, code = self.dying.pop(0)
            if pid in self.alive:
                self.alive.discard(pid)
                assert self.supervisor is not None
                self.supervisor.on_exit(pid, code)

    def group_alive(self, child: Child) -> bool:
        return child.pgid in self.alive

    def forget(self, child: Child) -> None:
        pass

    def exit(self, name: str, code: int) -> None:
        pid = self.pids[name]
        assert pid in self.alive, f"{name} is not running"
        self.alive.discard(pid)
        assert self.supervisor is not None
        self.supervisor.on_exit(pid, code)

    def starts(self, name: str) -> list[float]:
        return [t for t, n, _ in self.spawned if n == name]


class FakeRun:
    def __init__(self, plan: Plan, tmp: Path) -> None:
        self.clock = FakeClock()
        self.spawner = FakeSpawner()
        self.spawner.clock = self.clock
        self.out = io.StringIO()
        self.output = Output(stream=self.out, live=False, log_dir=tmp / "logs", no_color=True)
        self.sup = Supervisor(
            plan,
            spawner=self.spawner,
            output=self.output,
            clock=self.clock,
            log_dir=tmp / "logs",
            env={"PATH": os.environ.get("PATH", "")},
        )
        self.spawner.supervisor = self.sup

    def advance(self, dt: float, step: float = 0.05) -> None:
        end = self.clock.t + dt
        self.spawner.deliver()
        while self.clock.t < end - 1e-9:
            self.clock.t = min(end, self.clock.t + step)
            self.sup.tick()
            self.spawner.deliver()

    def text(self) -> str:
        return self.out.getvalue()


@pytest.fixture
def fake_run(tmp_path: Path):
    """fake_run(text) → a FakeRun of that YAML (or, with suffix=".launch.py", Python) description, started."""

    def make(text: str, arguments: dict[str, str] | None = None, start: bool = True, suffix: str = ".yaml") -> FakeRun:
        path = tmp_path / f"case{len(list(tmp_path.glob('case*')))}{suffix}"
        path.write_text(text)
        run = FakeRun(resolve(load(path), arguments or {}, str(path)), tmp_path)
        if start:
            run.sup.start()
        return run

    return make
