"""`diffctl launch` as a user runs it: a real launcher run that can never leak.

Every launcher started here gets a unique DIFFCTL_TEST_TAG in its environment, which all its descendants
inherit; `tagged(tag)` finds any of them still alive (even orphans re-parented to init), and teardown
SIGKILLs them, so a failing test leaves nothing behind either.
"""

from __future__ import annotations

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
