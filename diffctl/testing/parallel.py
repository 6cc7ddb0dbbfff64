"""Running test files in child processes, N at a time, each stopped at its timeout with everything reaped.

Each file runs in a process of its own session (`python -m diffctl.testing.child`: launch_testing files
through diffctl's launch_test, pytest files through pytest, those using launch_pytest on a bus of their own);
a test stopped at its timeout is interrupted first (SIGINT: its launch shuts its processes down as on Ctrl-C),
killed if it does not end within STOP_GRACE_S. `diffctl test` is a subreaper: whatever a test leaves behind
(processes of a launcher that was killed) is re-parented to it and killed, group and all, when the test ends.
"""

from __future__ import annotations

import ctypes
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


CHILD = [sys.executable, "-m", "diffctl.testing.child"]  # runs the file's runner, dying with this process


def command(test: TestFile, junit: Path, arguments: list[str], artifacts: Path | None) -> list[str]:
    if test.kind == "launch":
        argv = [*CHILD, "launch_test", str(test.path), *arguments, "--junit-xml", str(junit)]
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
STOP_GRACE_S = 3.0  # for a launch to interrupt its processes; stubborn ones are swept up after (sweep_orphans)


PR_SET_CHILD_SUBREAPER = 36


def become_subreaper() -> bool:
    """Orphans of this process's descendants are re-parented here (not to init): sweep_orphans finds them."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        return ctypes.CDLL(None, use_errno=True).prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0) == 0
    except (OSError, AttributeError):
        return False


def _signal_group(pgid: int, sig: int) -> None:
    try:
        os.killpg(pgid, sig)
    except (ProcessLookupError, PermissionError):
        pass


def _children_of(parent: int) -> list[int]:
    """The pids whose parent is `parent` (from /proc)."""
    out = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat", "rb") as f:
                fields = f.read().rsplit(b")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == parent:
            out.append(int(entry))
    return out


def sweep_orphans(keep: set[int]) -> None:
    """Kill (group and all) and reap every child of this process but `keep`: processes a dead test's launch
    left behind, re-parented here because this process is a subreaper."""
    if not sys.platform.startswith("linux"):
        return
    for pid in _children_of(os.getpid()):
        if pid in keep:
            continue
        try:
            _signal_group(os.getpgid(pid), signal.SIGKILL)
        except ProcessLookupError:
            pass
        try:
            os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
        except (ProcessLookupError, ChildProcessError):
            pass


def run_one(test: TestFile, junit: Path, arguments: list[str], timeout_s: float,
            artifacts: Path | None = None) -> Outcome:
    argv = command(test, junit, arguments, artifacts)
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
        _signal_group(proc.pid, signal.SIGINT)
        try:
            output, _ = proc.communicate(timeout=STOP_GRACE_S)
        except subprocess.TimeoutExpired:
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
    if not any(t.kind != "pytest" for t in tests) or os.environ.get(SHARED_ZYGOTE_ENV, "1").strip() == "0":
        return None
    from diffctl.supervision.fork_server import ForkServer, dies_with_launcher, enabled
    from diffctl.testing.zygotes import test_preload

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
        _signal_group(pid, signal.SIGINT)
        reader.join(STOP_GRACE_S)
        if reader.is_alive():
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
    # SIGKILL: what its launch leaves behind is swept up once it is reaped (sweep_orphans).
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    proc.wait()


def _stop_groups(pgids: list[int]) -> None:
    """Interrupt the tests' groups (their launches shut down), then kill what is left after STOP_GRACE_S."""
    for pgid in pgids:
        _signal_group(pgid, signal.SIGINT)
    deadline = time.monotonic() + STOP_GRACE_S
    while time.monotonic() < deadline and any(_group_alive(g) for g in pgids):
        time.sleep(0.05)
    for pgid in pgids:
        _kill_group(pgid)
    deadline = time.monotonic() + STOP_GRACE_S
    while time.monotonic() < deadline and any(_group_alive(g) for g in pgids):
        time.sleep(0.02)  # gone, so what they leave behind is re-parented here before the sweep


def _group_alive(pgid: int) -> bool:
    try:
        os.killpg(pgid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def run_all(tests: list[TestFile], *, jobs: int, junit_dir: Path, arguments: list[str], timeout_s: float,
            artifacts: Path | None, on_done: Callable[[Outcome], None]) -> list[Outcome]:
    lock = threading.Lock()
    outcomes: list[Outcome | None] = [None] * len(tests)
    become_subreaper()
    zygote = shared_zygote(tests)

    def keep() -> set[int]:
        with _RUNNING_LOCK:
            alive = {p.pid for p in _RUNNING} | set(_FORKED)
        return alive | ({zygote.process.pid} if zygote is not None else set())

    def one(index: int) -> None:
        test = tests[index]
        where = None
        if artifacts is not None:
            where = artifacts / f"{index:02d}-{test.path.name[:-3]}"
        junit = junit_dir / f"{index:03d}.xml"
        outcome = None
        if zygote is not None and test.kind != "pytest":
            outcome = run_one_forked(zygote, test, junit, arguments, timeout_s, where)
        if outcome is None:
            outcome = run_one(test, junit, arguments, timeout_s, where)
        outcomes[index] = outcome
        sweep_orphans(keep())
        with lock:
            on_done(outcome)

    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        try:
            list(pool.map(one, range(len(tests))))
        except BaseException:
            # Ctrl-C (or a bug here): the tests running in sessions of their own stop with us.
            pool.shutdown(wait=False, cancel_futures=True)
            with _RUNNING_LOCK:
                groups = [p.pid for p in _RUNNING] + list(_FORKED)
            _stop_groups(groups)
            raise
        finally:
            if zygote is not None:
                zygote.close(kill=True)
            sweep_orphans(set())
    return [o for o in outcomes if o is not None]
