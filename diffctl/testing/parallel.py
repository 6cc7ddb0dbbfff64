"""Running test files in child processes, N at a time, each stopped at its timeout with everything reaped.

Each file runs in a process of its own session (`python -m diffctl.testing.child`: launch_testing files through
diffctl's launch_test, pytest files through pytest, those using launch_pytest on a bus of their own); a launch test's processes die with it (death signal and the
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
from typing import Any

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
CHILD = [sys.executable, "-m", "diffctl.testing.child"]  # runs the file's runner, dying with this process


def use_fork_server(jobs: int) -> bool:
    """Off unless DIFFCTL_TEST_FORK_SERVER=1: on 2 cores, 8 smoke tests under -j 2 took as long with a zygote per
    test as without (26-32 s either way, four runs), and one test alone started its components later with it."""
    return os.environ.get(FORK_SERVER_ENV, "").strip() == "1"


def command(test: TestFile, junit: Path, arguments: list[str], artifacts: Path | None,
            fork_server: bool = False) -> list[str]:
    if test.kind == "launch":
        argv = [*CHILD, "launch_test", str(test.path), *arguments, "--junit-xml", str(junit)]
        if fork_server:
            argv.append("--fork-server")
        if test.package:
            argv += ["--package-name", test.package]
        if artifacts is not None:
            argv += ["--artifacts", str(artifacts)]
        return argv
    runner = "pytest-isolated" if test.kind == "launch_pytest" else "pytest"
    argv = [*CHILD, runner, str(test.path), "-p", "no:cacheprovider", "-q", f"--junit-xml={junit}"]
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


SHARED_ZYGOTE_ENV = "DIFFCTL_TEST_SHARED_ZYGOTE"
_FORKED: set[int] = set()


def shared_zygote(tests: list[TestFile]) -> Any:
    """One preloaded interpreter the launch tests of this run are forked from (zygotes.py); one test gains
    too (its components then import nothing: 3.8 → 1.9 s of CPU for the tutorial's smoke test).
    DIFFCTL_TEST_SHARED_ZYGOTE=0 turns it off."""
    if not any(t.kind == "launch" for t in tests) or os.environ.get(SHARED_ZYGOTE_ENV, "1").strip() == "0":
        return None
    from diffctl.launch_legacy.fork_server import ForkServer, dies_with_launcher, enabled
    from diffctl.testing.zygotes import become_subreaper, test_preload

    if not enabled(os.environ) or not become_subreaper():
        return None
    return ForkServer(dict(os.environ), preexec=dies_with_launcher(), preload=test_preload())


def run_one_forked(server: Any, test: TestFile, junit: Path, arguments: list[str], timeout_s: float,
                   artifacts: Path | None = None) -> Outcome | None:
    """A launch test forked from the shared zygote; None when the zygote cannot (then it is exec'd)."""
    argv = command(test, junit, arguments, artifacts)
    argv = [sys.executable, "-m", "diffctl", "test-child", *argv[len(CHILD):]]
    read_end, write_end = os.pipe()
    started = time.monotonic()
    try:
        with _RUNNING_LOCK:
            pid = server.spawn(argv, dict(os.environ), str(test.root) if test.root else None, write_end, write_end)
            if pid is not None:
                _FORKED.add(pid)
    finally:
        os.close(write_end)
    if pid is None:
        os.close(read_end)
        return None
    chunks: list[bytes] = []

    def read() -> None:
        with os.fdopen(read_end, "rb") as pipe:
            chunks.append(pipe.read())

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    reader.join(timeout_s)
    timed_out = reader.is_alive()
    if timed_out:
        _kill_group(pid)
        reader.join()
    try:
        _, status = os.waitpid(pid, 0)
        returncode = os.waitstatus_to_exitcode(status)
    except ChildProcessError:
        returncode = 1
    finally:
        with _RUNNING_LOCK:
            _FORKED.discard(pid)
    output = b"".join(chunks).decode(errors="replace")
    if timed_out:
        output += f"\n[diffctl test] {test.label}: timed out after {timeout_s:g} s; stopped it and its processes\n"
    return Outcome(test, returncode, output, time.monotonic() - started, timed_out, junit)


def _kill_group(pid: int) -> None:
    try:
        os.killpg(pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass


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
    zygote = None if fork else shared_zygote(tests)

    def one(index: int) -> None:
        test = tests[index]
        where = None
        if artifacts is not None:
            where = artifacts / f"{index:02d}-{test.path.name[:-3]}"
        junit = junit_dir / f"{index:03d}.xml"
        outcome = None
        if zygote is not None and test.kind == "launch":
            outcome = run_one_forked(zygote, test, junit, arguments, timeout_s, where)
        if outcome is None:
            outcome = run_one(test, junit, arguments, timeout_s, where, fork)
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
                forked = list(_FORKED)
            for proc in running:
                _kill_group(proc.pid)
            for pid in forked:
                _kill_group(pid)
            raise
        finally:
            if zygote is not None:
                zygote.close(kill=True)
    return [o for o in outcomes if o is not None]
