"""Running test files in child processes, N at a time, each stopped at its timeout with everything reaped.

Each file runs in a process of its own session (launch tests through `python -m diffctl.testing.launch_test`,
pytest files through `python -m pytest`); a launch test's processes die with it (death signal and the
launcher's guard), so killing that session at the timeout leaves nothing behind.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

from diffctl.testing.child import PARENT_ENV
from diffctl.testing.discovery import TestFile


@dataclass
class Outcome:
    test: TestFile
    returncode: int
    output: str
    seconds: float
    timed_out: bool = False
    junit: Path | None = None

    @property
    def ok(self) -> bool:
        return self.returncode == 0 and not self.timed_out


FORK_SERVER_ENV = "DIFFCTL_TEST_FORK_SERVER"
CHILD = [sys.executable, "-m", "diffctl.testing.child"]  # runs the module, dying with this process


def use_fork_server(jobs: int) -> bool:
    """Off unless DIFFCTL_TEST_FORK_SERVER=1: on 2 cores, 8 smoke tests under -j 2 took as long with a zygote per
    test as without (26-32 s either way, four runs), and one test alone started its components later with it."""
    return os.environ.get(FORK_SERVER_ENV, "").strip() == "1"


def command(test: TestFile, junit: Path, arguments: list[str], artifacts: Path | None,
            fork_server: bool = False) -> list[str]:
    if test.kind == "launch":
        argv = [*CHILD, "diffctl.testing.launch_test", str(test.path), *arguments, "--junit-xml", str(junit)]
        if fork_server:
            argv.append("--fork-server")
        if test.package:
            argv += ["--package-name", test.package]
        if artifacts is not None:
            argv += ["--artifacts", str(artifacts)]
        return argv
    argv = [*CHILD, "pytest", str(test.path), "-p", "no:cacheprovider", "-q", f"--junit-xml={junit}"]
    if test.package:
        argv.append(f"--junit-prefix={test.package}")
    if arguments:
        argv += ["--launch-args", *arguments]
    return argv


_RUNNING: set[subprocess.Popen] = set()
_RUNNING_LOCK = threading.Lock()


def run_one(test: TestFile, junit: Path, arguments: list[str], timeout_s: float,
            artifacts: Path | None = None, fork_server: bool = False) -> Outcome:
    argv = command(test, junit, arguments, artifacts, fork_server)
    started = time.monotonic()
    with _RUNNING_LOCK:
        proc = subprocess.Popen(
            argv,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
            cwd=str(test.root) if test.root else None,
            start_new_session=True,
            text=True,
            errors="replace",
            env={**os.environ, PARENT_ENV: str(os.getpid())},
        )
        _RUNNING.add(proc)
    timed_out = False
    try:
        output, _ = proc.communicate(timeout=timeout_s)
    except subprocess.TimeoutExpired:
        timed_out = True
        _kill_session(proc)
        output, _ = proc.communicate()
        output += f"\n[diffctl test] {test.label}: timed out after {timeout_s:g} s; stopped it and its processes\n"
    finally:
        if proc.poll() is None:
            _kill_session(proc)
        with _RUNNING_LOCK:
            _RUNNING.discard(proc)
    return Outcome(test, proc.returncode, output, time.monotonic() - started, timed_out, junit)


def _kill_session(proc: subprocess.Popen) -> None:
    # SIGKILL: the launch test's children follow through their death signal and the guard.
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    proc.wait()


def run_all(tests: list[TestFile], *, jobs: int, junit_dir: Path, arguments: list[str], timeout_s: float,
            artifacts: Path | None, on_done: Callable[[Outcome], None]) -> list[Outcome]:
    lock = threading.Lock()
    outcomes: list[Outcome | None] = [None] * len(tests)
    fork = use_fork_server(jobs)

    def one(index: int) -> None:
        test = tests[index]
        where = None
        if artifacts is not None:
            where = artifacts / f"{index:02d}-{test.path.name[:-3]}"
        outcome = run_one(test, junit_dir / f"{index:03d}.xml", arguments, timeout_s, where, fork)
        outcomes[index] = outcome
        with lock:
            on_done(outcome)

    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        try:
            list(pool.map(one, range(len(tests))))
        except BaseException:
            # Ctrl-C (or a bug here): the tests running in sessions of their own stop with us.
            pool.shutdown(wait=False, cancel_futures=True)
            with _RUNNING_LOCK:
                running = list(_RUNNING)
            for proc in running:
                try:
                    os.killpg(proc.pid, signal.SIGKILL)
                except (ProcessLookupError, PermissionError):
                    pass
            raise
    return [o for o in outcomes if o is not None]
